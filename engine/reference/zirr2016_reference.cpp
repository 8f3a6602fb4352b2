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

float binomial(float N, float p, glm::uvec3 seed) {
    if (!(N > 0.0f) || !(p > 0.0f)) return 0.0f;
    p = std::min(p, 1.0f);
    float mean = N * p;
    if (mean > 5.0f) {
        glm::uvec3 r = hash3(seed);
        float g = std::sqrt(-2.0f * std::log(unit(r.x))) * std::cos(2.0f * kPi * unit(r.y));
        return std::clamp(std::floor(mean + std::sqrt(mean * (1.0f - p)) * g), 0.0f, N);
    }
    bool few = N <= float(kMaxTrials);
    int trials = few ? int(std::ceil(N)) : kMaxTrials;
    float pTrial = few ? p : mean / float(kMaxTrials);
    float count = 0.0f;
    glm::uvec3 state = seed;
    for (int i = 0; i < trials; ++i) {
        state = hash3(state + glm::uvec3(uint32_t(i), 0u, 0u));
        float q = few ? pTrial * std::min(1.0f, N - float(i)) : pTrial;
        count += unit(state.x) < q ? 1.0f : 0.0f;
    }
    return count;
}

Footprint footprint(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy, const Params& params) {
    // Ellipse axes from J J^T (shaders/common/footprint.glsl).
    double a = double(duvdx.x) * duvdx.x + double(duvdy.x) * duvdy.x;
    double b = double(duvdx.x) * duvdx.y + double(duvdy.x) * duvdy.y;
    double c = double(duvdx.y) * duvdx.y + double(duvdy.y) * duvdy.y;
    double mean = 0.5 * (a + c), diff = 0.5 * (a - c), root = std::sqrt(diff * diff + b * b);
    double l1 = mean + root;
    double major = std::max(std::sqrt(std::max(l1, 1e-24)), 1e-20);
    double detJ = std::abs(double(duvdx.x) * duvdy.y - double(duvdx.y) * duvdy.x);  // major x minor
    double minor = std::max(std::clamp(detJ / major, 1e-12, major), major * 1e-6);
    glm::dvec2 dir = std::abs(b) > 1e-30 ? glm::dvec2(l1 - c, b) : (a >= c ? glm::dvec2(1, 0) : glm::dvec2(0, 1));
    dir = glm::normalize(dir);
    Footprint f;
    f.ratio = float(major / minor);
    f.samples = std::clamp(int(std::ceil(f.ratio)), 1, kMaxAnisotropy);
    double coveredMinor = std::max(minor, major / kMaxAnisotropy);
    f.lod = float(std::clamp(std::log2(coveredMinor * params.screenSpaceScale), -100.0, 100.0));
    f.lod0 = int(std::floor(f.lod));
    f.lodT = f.lod - std::floor(f.lod);
    f.sampleStep = glm::vec2(dir * (2.0 * major / f.samples));
    f.firstSample = uv - glm::vec2(dir * major) + 0.5f * f.sampleStep;
    return f;
}

float glintD(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy, glm::vec3 h, float alpha, int ndf, const Params& params) {
    Footprint fp = footprint(uv, duvdx, duvdy, params);
    auto D = [&](glm::vec3 v) {
        return float(ndf == 0 ? reference::ggxD(glm::dvec3(v), alpha) : reference::beckmannD(glm::dvec3(v), alpha));
    };
    float Dn = D({0, 0, 1});
    float R = params.microfacetRoughness;
    float p = std::clamp(R * D(h) / Dn, 0.0f, 1.0f);
    float cellSize = std::sqrt(R / Dn);
    glm::vec2 q = glm::vec2(h) / cellSize - 0.5f;
    glm::vec2 qBase = glm::floor(q), f = q - qBase;
    glm::ivec2 a0(qBase);
    float angular[4] = {(1 - f.x) * (1 - f.y), f.x * (1 - f.y), (1 - f.x) * f.y, f.x * f.y};
    float density = std::exp(std::clamp(params.logDensity, 0.0f, 50.0f));
    float facetsLo = density * std::exp2(2.0f * fp.lod0);
    float level[2] = {0, 0};
    for (int l = 0; l < 2; ++l) {
        int lod = fp.lod0 + l;
        float facets = facetsLo * (l == 0 ? 1.0f : 4.0f);
        float invSize = std::exp2(-float(lod));
        for (int j = 0; j < fp.samples; ++j) {
            glm::ivec2 texel(glm::floor((fp.firstSample + float(j) * fp.sampleStep) * invSize));
            for (int a = 0; a < 4; ++a) {
                glm::ivec2 cell = a0 + glm::ivec2(a & 1, a >> 1);
                glm::uvec3 seed(uint32_t(texel.x), uint32_t(texel.y),
                                hash3(glm::uvec3(uint32_t(lod + 4096), uint32_t(cell.x), uint32_t(cell.y))).x);
                level[l] += angular[a] * binomial(facets, p, seed);
            }
        }
        level[l] /= std::max(facets * float(fp.samples), 1e-30f);
    }
    return facetsLo > 0.0f ? Dn / R * ((1.0f - fp.lodT) * level[0] + fp.lodT * level[1]) : 0.0f;
}

}  // namespace glimmer::zirr2016
