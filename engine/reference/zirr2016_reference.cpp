#include "reference/zirr2016_reference.h"

#include <algorithm>
#include <cmath>

#include "reference/brdf_reference.h"

namespace glimmer::zirr2016 {

static constexpr float kPi = 3.14159265358979323846f;

glm::uvec3 hash3(glm::uvec3 v) {
    v = v * 747796405u + 2891336453u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return v;
}

static float unit(uint32_t bits) { return (float(bits >> 8u) + 0.5f) * (1.0f / 16777216.0f); }

float inverseNormal(float u) {
    float q = std::min(u, 1.0f - u);
    float t = std::sqrt(-2.0f * std::log(q));
    float x = t - (2.515517f + t * (0.802853f + t * 0.010328f)) /
                      (1.0f + t * (1.432788f + t * (0.189269f + t * 0.001308f)));
    return u < 0.5f ? -x : x;
}

float binomial(float N, float p, float u) {
    if (!(N > 0.0f) || !(p > 0.0f)) return 0.0f;
    p = std::min(p, 1.0f);
    if (N < 1.0f) return u < N * p ? 1.0f : 0.0f;
    if (p >= 1.0f) return std::floor(N);
    float mean = N * p;
    if (mean > 5.0f)
        return std::clamp(std::floor(mean + std::sqrt(mean * (1.0f - p)) * inverseNormal(u) + 0.5f), 0.0f,
                          std::floor(N));
    float logMiss = p < 0.05f ? -p * (1.0f + p * (0.5f + p * (1.0f / 3.0f + p * 0.25f))) : std::log(1.0f - p);
    float pmf = std::exp(N * logMiss), cdf = pmf;
    float odds = p / std::max(1.0f - p, 1e-30f);
    float k = 0.0f;
    for (int i = 0; i < kMaxPmfSteps && u >= cdf && k < N; ++i) {
        pmf *= (N - k) / (k + 1.0f) * odds;
        k += 1.0f;
        cdf += pmf;
    }
    return std::min(k, std::floor(N));
}

Footprint footprint(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy) {
    glm::vec2 extent = glm::abs(duvdx) + glm::abs(duvdy);
    float longSide = std::max(std::max(extent.x, extent.y), 1e-20f);
    float shortSide = std::max(std::min(extent.x, extent.y), longSide * 1e-6f);
    Footprint f;
    f.ratio = longSide / shortSide;
    f.steps = std::clamp(int(std::ceil(f.ratio)), 1, kMaxSteps);
    float covered = std::max(shortSide, longSide / float(kMaxSteps));
    f.lod = std::clamp(std::log2(covered), -100.0f, 100.0f);
    f.lod0 = int(std::floor(f.lod));
    f.lodT = f.lod - std::floor(f.lod);
    glm::vec2 dir = extent.x >= extent.y ? glm::vec2(1, 0) : glm::vec2(0, 1);
    f.stepUv = dir * (longSide / float(f.steps));
    f.firstStep = uv - dir * (0.5f * longSide) + 0.5f * f.stepUv;
    return f;
}

float glintD(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy, glm::vec3 h, float alpha, int ndf, const Params& params) {
    Footprint fp = footprint(uv, duvdx, duvdy);
    float density = std::exp(std::clamp(params.logDensity, 0.0f, 50.0f));
    float facetsLo = density * std::exp2(2.0f * fp.lod0);
    if (h.z <= 0.0f || !(facetsLo > 0.0f)) return 0.0f;
    float D = float(ndf == 0 ? reference::ggxD(glm::dvec3(h), alpha) : reference::beckmannD(glm::dvec3(h), alpha));
    float gamma = params.searchCone;
    float p = std::clamp(D * h.z * kPi * gamma * gamma, 0.0f, 1.0f);
    if (!(p > 0.0f)) return 0.0f;
    glm::ivec2 cone(glm::floor(glm::vec2(h) / (2.0f * gamma)));
    float level[2] = {0, 0};
    for (int l = 0; l < 2; ++l) {
        int lod = fp.lod0 + l;
        float facets = facetsLo * (l == 0 ? 1.0f : 4.0f);
        float invSize = std::exp2(-float(lod));
        uint32_t levelSeed = hash3(glm::uvec3(uint32_t(lod + 4096), uint32_t(cone.x), uint32_t(cone.y))).x;
        for (int j = 0; j < fp.steps; ++j) {
            glm::vec2 q = (fp.firstStep + float(j) * fp.stepUv) * invSize - 0.5f;
            glm::vec2 base = glm::floor(q), f = q - base;
            glm::ivec2 c0(base);
            for (int a = 0; a < 4; ++a) {
                glm::ivec2 o(a & 1, a >> 1);
                float w = (o.x == 1 ? f.x : 1.0f - f.x) * (o.y == 1 ? f.y : 1.0f - f.y);
                glm::ivec2 cell = c0 + o;
                float u = unit(hash3(glm::uvec3(uint32_t(cell.x), uint32_t(cell.y), levelSeed)).x);
                level[l] += w * binomial(facets, p, u);
            }
        }
        level[l] /= facets * float(fp.steps);
    }
    float ratioToMean = ((1.0f - fp.lodT) * level[0] + fp.lodT * level[1]) / p;
    return D * std::min(ratioToMean, params.dynamicRange);
}

}  // namespace glimmer::zirr2016
