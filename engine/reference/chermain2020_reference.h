// CPU reference of Chermain et al. 2020 (shaders/glints/chermain2020/chermain2020.glsl) without the 2021
// anti-aliasing: the same footprint, levels, EWA cells, hash, density randomization, rotation, target whitening
// (and GGX warp) and dictionary lookups (linear between texel centres, mirrored at 0, as the GL samples the
// table), in float where the shader's integer decisions depend on it. Tests hold the shader to it and read the
// cells' choices (marginals, level) from it.
#pragma once
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "glints/chermain2020/dictionary.h"

namespace glimmer::chermain2020 {

// The method's parameters that the reference reads (the defaults of the chermain2020 table entry).
struct ReferenceParams {
    float logDensity = 27.0f, relativeArea = 1.0f, densityRandomization = 2.0f, maxAnisotropy = 8.0f;
    float lodBias = 0.0f, roughnessAnisotropy = 1.0f, slopeCorrelation = 0.0f, glintAnisotropy = 1.0f, seed = 0.0f;
    float lobeCount = 0.0f;   // 0 clamped (authors), 1 material (ours: sparse cells emptied, lobes thinned)
    float glintAngle = 0.0f;  // gamma: with lobeCount 1, the lobe thinning only (the widening is not modelled)
};

// The shader's 4D integer hash and the inverse normal CDF it draws the density randomization with.
std::array<uint32_t, 4> hash4(std::array<uint32_t, 4> v);
float probit(float p);

// What Alg. 3 draws for one cell of a level (the coherent index of Eq. 8 included).
struct CellDraw {
    bool empty = false;      // removed by the relative area
    int dictionaryLevel = 0; // l_dist, CHERMAIN_LEVELS = the smooth NDF
    int marginalX = 0, marginalY = 0;
    float theta = 0.0f;      // rotation, radians
    float scale = 1.0f;      // 1 / the probability of holding microfacets (lobe_count = material)
};
CellDraw drawCell(const ReferenceParams& params, int level, glm::ivec2 cell, float log4n, int levels);

// One glintD evaluation: the P-NDF D(h) for a pixel of UV `uv` with derivatives duvdx, duvdy, roughness alpha,
// NDF 0 GGX / 1 Beckmann, density scale, half vector h in the shading frame.
double referenceD(const Dictionary& dictionary, const ReferenceParams& params, glm::vec2 uv, glm::vec2 duvdx,
                  glm::vec2 duvdy, glm::vec3 h, float alpha, int ndf, float densityScale = 1.0f);

// The cells with non-zero EWA weight of the single level a footprint selects when its level blend is 0, with
// their weights (normalized) and draws: for lobe counting.
struct WeightedCell {
    glm::ivec2 cell;
    double weight;
    CellDraw draw;
};
std::vector<WeightedCell> footprintCells(const ReferenceParams& params, glm::vec2 uv, glm::vec2 duvdx,
                                         glm::vec2 duvdy, int levels, float densityScale = 1.0f);

}  // namespace glimmer::chermain2020
