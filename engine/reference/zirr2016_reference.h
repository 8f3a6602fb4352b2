// CPU reference of the Zirr & Kaplanyan 2016 baseline as its authors' shader runs it (shaders/glints/zirr2016/zirr2016.glsl):
// the axis-aligned +-0.5 px box footprint, the LOD and step choice (16-step cap), the inverse-CDF binomial of one
// uniform and the whole glintD, in float like the shader, so tests can compare the shader with it value by value.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

namespace glimmer::zirr2016 {

constexpr int kMaxSteps = 16;
constexpr int kMaxPmfSteps = 16;

struct Params {
    float logDensity = 16.0f, searchCone = 0.01f, dynamicRange = 50000.0f;
};

struct Footprint {
    float ratio = 1, lod = 0;
    int steps = 1, lod0 = 0;
    float lodT = 0;
    glm::vec2 firstStep{0.0f}, stepUv{0.0f};
};

glm::uvec3 hash3(glm::uvec3 v);
float inverseNormal(float u);                 // A&S 26.2.23
float binomial(float N, float p, float u);    // inverse CDF of b(N, p) at u
Footprint footprint(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy);
// glintD for the shading frame half vector h (GGX when ndf == 0, else Beckmann), density scale 1.
float glintD(glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy, glm::vec3 h, float alpha, int ndf, const Params& params);

}  // namespace glimmer::zirr2016
