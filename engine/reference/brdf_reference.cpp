#include "reference/brdf_reference.h"

#include <algorithm>
#include <cmath>

namespace glimmer::reference {

constexpr double kPi = 3.14159265358979323846;

double ggxD(const glm::dvec3& h, double alpha) {
    if (h.z <= 0.0) return 0.0;
    double a2 = alpha * alpha, c2 = h.z * h.z;
    double d = c2 * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

double beckmannD(const glm::dvec3& h, double alpha) {
    if (h.z <= 0.0) return 0.0;
    double c2 = h.z * h.z, tan2 = (1.0 - c2) / c2, a2 = alpha * alpha;
    return std::exp(-tan2 / a2) / (kPi * a2 * c2 * c2);
}

double ggxG1(const glm::dvec3& w, double alpha) {
    if (w.z <= 0.0) return 0.0;
    double c2 = w.z * w.z, tan2 = std::max(1.0 - c2, 0.0) / c2;
    return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}

double beckmannG1(const glm::dvec3& w, double alpha) {
    if (w.z <= 0.0) return 0.0;
    double tanTheta = std::sqrt(std::max(1.0 - w.z * w.z, 0.0)) / w.z;
    if (tanTheta <= 0.0) return 1.0;
    double a = 1.0 / (alpha * tanTheta);
    if (a >= 1.6) return 1.0;
    return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

glm::dvec3 schlickFresnel(const glm::dvec3& f0, double cosTheta) {
    double m = std::clamp(1.0 - cosTheta, 0.0, 1.0);
    return f0 + (glm::dvec3(1.0) - f0) * std::pow(m, 5.0);
}

glm::dvec3 shadeDirectional(const SurfacePoint& s, const glm::dvec3& wi, const glm::dvec3& wo,
                            const glm::dvec3& irradiance, const glm::dvec3& ambient) {
    glm::dvec3 diffuseAlbedo = (1.0 - s.metallic) * s.baseColor;
    glm::dvec3 radiance = ambient * diffuseAlbedo;
    if (wi.z <= 0.0 || wo.z <= 0.0) return radiance;
    glm::dvec3 h = glm::normalize(wi + wo);
    double D = s.beckmann ? beckmannD(h, s.alpha) : ggxD(h, s.alpha);
    double G = s.beckmann ? beckmannG1(wi, s.alpha) * beckmannG1(wo, s.alpha) : ggxG1(wi, s.alpha) * ggxG1(wo, s.alpha);
    glm::dvec3 f0 = glm::mix(glm::dvec3(0.04), s.baseColor, s.metallic);
    glm::dvec3 F = schlickFresnel(f0, std::max(glm::dot(wi, h), 0.0));
    glm::dvec3 specular = D * G * F / (4.0 * wi.z * wo.z);
    return radiance + (diffuseAlbedo / kPi + specular) * irradiance * wi.z;
}

}  // namespace glimmer::reference
