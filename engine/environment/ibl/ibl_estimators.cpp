#include "environment/ibl/ibl_estimators.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace glimmer::ibl {

namespace {
constexpr double kPi = std::numbers::pi;
}

double radicalInverse2(unsigned bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return double(bits) * 2.3283064365386963e-10;
}

double cubeTexelSolidAngleAt(glm::dvec3 d, int faceSize) {
    glm::dvec3 a = glm::abs(d);
    double dist = glm::length(d) / std::max({a.x, a.y, a.z});   // distance to the unit cube
    double texelArea = 4.0 / (double(faceSize) * faceSize);
    return texelArea / (dist * dist * dist);
}

glm::dvec3 regularLobe(glm::dvec3 wo, const KurtLobe& lobe, const RegularPattern& pattern,
                       const EnvironmentLookup& env, int faceSize, double mipBias) {
    const double area = lobeCrossSectionArea(wo, lobe.mx, lobe.my, pattern.params.xi0);   // Eq. 14-15
    const int n = pattern.size();
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& h : pattern.halfVectors) {
        glm::dvec3 wi = reflectAbout(wo, h);
        double ih = glm::dot(wi, h);
        if (wi.z <= 0.0 || ih <= 0.0) continue;   // below the surface: no contribution, still counted in n
        double pixels = pixelsPerSample(area, faceSize * faceSize, n, wi, ih);   // Eq. 16
        double lod = mipLevelForSample(pixels, mipBias);
        double pdf = pattern.pdfConstant / (4.0 * ih);   // Eq. 17-18
        sum += env(wi, lod) * (kurtLobe(wi, wo, lobe) / pdf * wi.z);
    }
    return lobe.ks * sum / double(n);
}

glm::dvec3 fisLobe(glm::dvec3 wo, const KurtLobe& lobe, int numSamples, glm::dvec2 rotation,
                   const EnvironmentLookup& env, int faceSize, double mipBias) {
    glm::dvec3 sum(0.0);
    for (int i = 0; i < numSamples; ++i) {
        double u1 = std::fmod((i + 0.5) / numSamples + rotation.x, 1.0);
        double u2 = std::fmod(radicalInverse2(unsigned(i)) + rotation.y, 1.0);
        glm::dvec3 h = sampleKurtHalfVector(1.0 - u1, u2, lobe.mx, lobe.my);   // xi1 in (0, 1]
        glm::dvec3 wi = reflectAbout(wo, h);
        double oh = glm::dot(wo, h);
        if (wi.z <= 0.0 || oh <= 0.0) continue;
        double pdf = kurtHalfVectorPdf(h, lobe.mx, lobe.my) / (4.0 * oh);   // Eq. 10
        double omegaS = 1.0 / (numSamples * pdf);
        double omegaP = cubeTexelSolidAngleAt(wi, faceSize);
        double lod = std::max(0.5 * std::log2(omegaS / omegaP) + 1.0 + mipBias, 0.0);
        sum += env(wi, lod) * (kurtLobe(wi, wo, lobe) / pdf * wi.z);
    }
    return lobe.ks * sum / double(numSamples);
}

glm::dvec3 quadratureLobe(glm::dvec3 wo, const KurtLobe& lobe, const EnvironmentLookup& env, int thetaSteps,
                          int phiSteps) {
    glm::dvec3 sum(0.0);
    // Substitution theta = t^2 (pi/2) concentrates nodes near the pole where narrow lobes live.
    for (int it = 0; it < thetaSteps; ++it) {
        double t = (it + 0.5) / thetaSteps;
        double theta = t * t * 0.5 * kPi;
        double dTheta = 2.0 * t * 0.5 * kPi / thetaSteps;
        for (int ip = 0; ip < phiSteps; ++ip) {
            double phi = 2.0 * kPi * (ip + 0.5) / phiSteps;
            glm::dvec3 h{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
            double dOmegaH = std::sin(theta) * dTheta * (2.0 * kPi / phiSteps);
            glm::dvec3 wi = reflectAbout(wo, h);
            double oh = glm::dot(wo, h);
            if (wi.z <= 0.0 || oh <= 0.0) continue;
            sum += env(wi, 0.0) * (kurtLobe(wi, wo, lobe) * wi.z * 4.0 * oh * dOmegaH);
        }
    }
    return lobe.ks * sum;
}

}  // namespace glimmer::ibl
