// Chermain et al. 2020: the dictionary of multiscale 1D marginal slope distributions, generated and cached
// by engine/glints/chermain2020/dictionary.cpp and uploaded by engine/glints/chermain2020/resources.cpp.
// Texture: a 1D array, RGBA16F, CHERMAIN_TEXELS texels per row with its full mip chain (GL box filter: each level
// keeps the integral, so the filtered marginals stay normalized, Chermain et al. 2021's GGAA). Row
// level * CHERMAIN_ROWS_PER_LEVEL + m / 4 holds marginals m .. m + 3 of that level in R, G, B, A. Texel j holds the
// marginal at slope |x| = (j + 0.5) / CHERMAIN_TEXELS * 4 sigma_dict; beyond 4 sigma_dict the marginal is 0.
// Wrap: mirrored repeat (the marginals are even: linear filtering across 0 reads the mirror image).
// These constants must match chermain2020::DictionarySpec's defaults (tests/chermain2020_test.cpp checks).
#include "common/bindings.glsl"

layout(binding = UNIT_METHOD_FIRST) uniform sampler1DArray u_chermainDictionary;

const int CHERMAIN_LEVELS = 16;          // L (authors: 16)
const int CHERMAIN_MARGINALS = 192;      // N (authors: 192)
const int CHERMAIN_ROWS_PER_LEVEL = 48;  // N / 4
const int CHERMAIN_TEXELS = 64;          // per marginal (authors: 64)
const float CHERMAIN_ALPHA_DICT = 0.5;   // alpha_dist (authors: 0.5)
const float CHERMAIN_LOBE_STD = 0.02;    // sigma_lobe in dictionary slope units (authors: 0.02)
const float CHERMAIN_SIGMA_DICT = 0.35355339;   // alpha_dist / sqrt(2)
const float CHERMAIN_RANGE = 1.41421356;        // 4 sigma_dict: the table's extent in slope

// Marginal `m` of dictionary level `level` at |slope| / range `t` (in [0, 1]), at mip level `lod` (0 = the table).
float chermainMarginalLod(int level, int m, float t, float lod) {
    vec4 four = textureLod(u_chermainDictionary, vec2(t, float(level * CHERMAIN_ROWS_PER_LEVEL + (m >> 2))), lod);
    return four[m & 3];
}

// The same, filtered by the hardware over the footprint [t - |dx|, t + |dx|] x [t - |dy|, t + |dy|] (Chermain et
// al. 2021: geometric glint anti-aliasing; the derivatives are in texture coordinates).
float chermainMarginalGrad(int level, int m, float t, float dx, float dy) {
    vec4 four = textureGrad(u_chermainDictionary, vec2(t, float(level * CHERMAIN_ROWS_PER_LEVEL + (m >> 2))), dx, dy);
    return four[m & 3];
}
