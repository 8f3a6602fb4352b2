#include "reference/wang2020_reference.h"

#include <algorithm>
#include <cmath>

#include "glints/wang2020/wang2020_dpf.h"

namespace glimmer::wang2020 {

ReferenceResult explicitParticleD(const Quadtree& tree, const Footprint& fp, glm::vec3 wi, glm::vec3 wo, float alpha,
                                  float gamma) {
    ReferenceResult r;
    float cosGamma = std::cos(gamma);
    forEachParticle(tree, fp, alpha, [&](const Particle& p) {
        ++r.inFootprint;
        float im = glm::dot(wi, p.normal);
        if (im <= 0.0f) return;  // the particle faces away from the light
        glm::vec3 reflected = 2.0f * im * p.normal - wi;
        if (glm::dot(reflected, wo) >= cosGamma) ++r.reflecting;  // Eq. 4: 1_Omega(h_k) 1_A(x_k)
    });
    glm::vec3 h = glm::normalize(wi + wo);
    double expected = tree.particles * fp.area();
    if (expected <= 0.0 || h.z <= 1e-4f) return r;
    // Eq. 3 with D^ = reflecting / N, expressed as the D that Cook-Torrance's D G F / (4 cos cos) expects.
    r.D = float(4.0 * glm::dot(wi, h) * r.reflecting / (expected * coneSolidAngle(gamma) * h.z));
    return r;
}

glm::vec2 prefilteredConstantEnvironment(const DpfTable& dpf, float alpha, float gamma, glm::vec3 wo,
                                         PrefilterEstimator estimator) {
    const int K = 64;
    auto radicalInverse = [](uint32_t bits) {
        bits = (bits << 16u) | (bits >> 16u);
        bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
        bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
        bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
        bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
        return float(double(bits) * 2.3283064365386963e-10);
    };
    const float cosGamma = std::cos(gamma), sigma = coneSolidAngle(gamma);
    const glm::vec3 coneX = glm::normalize(
        glm::cross(std::abs(wo.z) < 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f), wo));
    const glm::vec3 coneY = glm::cross(wo, coneX);
    double radiance = 0.0;
    for (int j = 0; j < K; ++j) {
        float u1 = (j + 0.5f) / K, u2 = radicalInverse(uint32_t(j));
        float tan2 = -alpha * alpha * std::log(1.0f - u1);
        float cosM = 1.0f / std::sqrt(1.0f + tan2), sinM = std::sqrt(std::max(0.0f, 1.0f - cosM * cosM));
        glm::vec3 m(sinM * std::cos(2 * kPi * u2), sinM * std::sin(2 * kPi * u2), cosM);
        glm::vec3 toward = wo;
        if (estimator == PrefilterEstimator::Cone) {  // R2 sequence, uniform over the cone (as the shader)
            float v1 = std::fmod(0.5f + float(j) * 0.75487766f, 1.0f), v2 = std::fmod(0.5f + float(j) * 0.56984029f, 1.0f);
            float cosT = 1.0f - v1 * (1.0f - cosGamma), sinT = std::sqrt(std::max(1.0f - cosT * cosT, 0.0f));
            toward = glm::normalize(sinT * std::cos(2 * kPi * v2) * coneX + sinT * std::sin(2 * kPi * v2) * coneY +
                                    cosT * wo);
            if (toward.z <= 0.0f) continue;
        }
        float om = glm::dot(toward, m);
        if (om <= 0.0f) continue;
        glm::vec3 wi = 2.0f * om * m - toward;
        if (wi.z <= 0.0f) continue;
        glm::vec3 h = estimator == PrefilterEstimator::Cone ? glm::normalize(wi + wo) : m;  // half vector of i, o
        float M = glm::dot(wi, h) * smithG1Beckmann(wi, alpha) * smithG1Beckmann(wo, alpha) / (h.z * wo.z);
        if (estimator == PrefilterEstimator::Cone) {
            radiance += sigma * M;
        } else {
            float P = std::min(dpf.lookup(wi, wo), 1.0f);
            float pdf = beckmannD(m, alpha) * m.z / (4.0f * om);
            radiance += P * M / std::max(pdf, 1e-12f);
        }
    }
    double filtered = 0.0;
    for (int k = 0; k < 9; ++k)
        for (int l = 0; l < 36; ++l) {
            float cosI = 1.0f - (k + 0.5f) / 9.0f, sinI = std::sqrt(1.0f - cosI * cosI),
                  phi = (l + 0.5f) / 36.0f * 2 * kPi;
            filtered += std::min(dpf.lookup(glm::vec3(sinI * std::cos(phi), sinI * std::sin(phi), cosI), wo), 1.0f);
        }
    return {float(radiance / K), float(filtered * 2.0 * kPi / (36 * 9))};
}

float smithG1Beckmann(glm::vec3 w, float alpha) {
    if (w.z <= 0.0f) return 0.0f;
    float tanTheta = std::sqrt(std::max(0.0f, 1.0f - w.z * w.z)) / w.z;
    if (tanTheta <= 0.0f) return 1.0f;
    float a = 1.0f / (alpha * tanTheta);
    if (a >= 1.6f) return 1.0f;
    return (3.535f * a + 2.181f * a * a) / (1.0f + 2.276f * a + 2.577f * a * a);
}

}  // namespace glimmer::wang2020
