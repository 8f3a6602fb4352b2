// CPU reference of the Zirr & Kaplanyan 2016 baseline (shaders/glints/zirr2016.glsl): footprint coverage with the
// 16-texel anisotropy cap, the LOD choice, the binomial (Gaussian above N p = 5, Bernoulli trials below) and the
// whole glintD, in float like the shader, so tests can compare the shader with it value by value.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

namespace glimmer::zirr2016 {

constexpr int kMaxAnisotropy = 16;
constexpr int kMaxTrials = 16;

struct Params {
    float logDensity = 16.0f, microfacetRoughness = 0.005f, screenSpaceScale = 1.5f;
};

struct Footprint {
    float ratio = 1, lod = 0;
    int samples = 1, lod0 = 0;
    float lodT = 0;
    glm::vec2 firstSample{0.0f}, sampleStep{0.0f};
};

glm::uvec3 hash3(glm::uvec3 v);
float binomial(float N, float p, glm::uvec3 seed);
Footprint footprint(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy, const Params& params);
// glintD for the shading frame half vector h (GGX when ndf == 0, else Beckmann), density scale 1.
float glintD(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy, glm::vec3 h, float alpha, int ndf, const Params& params);

}  // namespace glimmer::zirr2016
