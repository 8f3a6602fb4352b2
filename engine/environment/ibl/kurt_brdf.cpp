#include "environment/ibl/kurt_brdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glimmer::ibl {

namespace {
constexpr double kPi = std::numbers::pi;
}

double kurtQ(glm::dvec3 h, double mx, double my) {
    if (h.z <= 0.0) return 0.0;
    double cos2 = h.z * h.z;
    double sin2 = std::max(0.0, 1.0 - cos2);
    if (sin2 <= 0.0) return 1.0;
    // tan^2 theta * cos^2 phi = hx^2 / hz^2, tan^2 theta * sin^2 phi = hy^2 / hz^2.
    double e = (h.x * h.x / (mx * mx) + h.y * h.y / (my * my)) / cos2;
    return std::exp(-e);
}

double kurtD(glm::dvec3 h, double mx, double my) {
    if (h.z <= 0.0) return 0.0;
    double c2 = h.z * h.z;
    return kurtQ(h, mx, my) / (kPi * mx * my * c2 * c2);
}

double schlickFresnel(double u, double r0) {
    double m = std::clamp(1.0 - u, 0.0, 1.0);
    double m2 = m * m;
    return r0 + (1.0 - r0) * m2 * m2 * m;
}

glm::dvec3 halfVector(glm::dvec3 wi, glm::dvec3 wo) { return glm::normalize(wi + wo); }

glm::dvec3 reflectAbout(glm::dvec3 wo, glm::dvec3 h) { return 2.0 * glm::dot(wo, h) * h - wo; }

double kurtLobe(glm::dvec3 wi, glm::dvec3 wo, const KurtLobe& lobe) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;
    glm::dvec3 h = halfVector(wi, wo);
    double oh = glm::dot(wo, h);
    if (oh <= 0.0) return 0.0;
    double f = schlickFresnel(oh, lobe.r0);
    double d = kurtD(h, lobe.mx, lobe.my);
    return f * d / (4.0 * oh * std::pow(wi.z * wo.z, lobe.alpha));
}

double kurtBrdf(glm::dvec3 wi, glm::dvec3 wo, const KurtMaterial& material) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;
    double sum = material.kd / kPi;
    for (const KurtLobe& lobe : material.lobes) sum += lobe.ks * kurtLobe(wi, wo, lobe);
    return sum;
}

glm::dvec3 sampleKurtHalfVector(double xi1, double xi2, double mx, double my) {
    double a = 2.0 * kPi * xi2;
    double phi = std::atan2(my * std::sin(a), mx * std::cos(a));   // Eq. 6
    double c = std::cos(phi), s = std::sin(phi);
    double tan2 = -std::log(xi1) / (c * c / (mx * mx) + s * s / (my * my));   // Eq. 7 (squared)
    double cosTheta = 1.0 / std::sqrt(1.0 + tan2);
    double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    return {sinTheta * c, sinTheta * s, cosTheta};
}

double kurtHalfVectorPdf(glm::dvec3 h, double mx, double my) {
    if (h.z <= 0.0) return 0.0;
    return kurtQ(h, mx, my) / (kPi * mx * my * h.z * h.z * h.z);
}

double kurtPdf(glm::dvec3 wi, glm::dvec3 wo, double mx, double my) {
    glm::dvec3 h = halfVector(wi, wo);
    double oh = glm::dot(wo, h);
    if (h.z <= 0.0 || oh <= 0.0) return 0.0;
    return kurtHalfVectorPdf(h, mx, my) / (4.0 * oh);
}

}  // namespace glimmer::ibl
