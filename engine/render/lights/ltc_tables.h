// The linearly transformed cosine tables of the area lights (Heitz, Dupuy, Hill, Neubelt 2016), fitted at build
// time by tools/ltc_fit (glimmer_ltc_fit writes the generated ltc_tables.cpp that defines kTableData).
// Layout: kLayers layers of kTableSize x kTableSize RGBA entries; row r (the texture's y) holds roughness
// alpha = max((r / (size - 1))^2, 1e-3), column c (x) holds cos(theta_v) = max(1 - (c / (size - 1))^2, 1e-3)
// (tools/ltc_fit/ltc_fitter.h rowAlpha, columnCosTheta). The GPU samples it at (sqrt(1 - cos theta), sqrt(alpha)),
// texel centres at the ends (shaders/lights/ltc.glsl).
//   0, 1: M^-1 of the specular lobe (BRDF x cosine, Fresnel 1), GGX then Beckmann, as (a, b, c, d) of
//         [[a, 0, b], [0, 1, 0], [c, 0, d]] in the frame (tangent towards the view, bitangent, normal);
//   2, 3: M^-1 of the NDF-only lobe D(h) / (4 |v.h|) (Kneiphof & Klein 2024's dedicated LTC), GGX, Beckmann;
//   4, 5: per NDF (GGX, Beckmann): the specular lobe's split-sum terms A and B (its integral is f0 A + B with
//         Schlick's Fresnel) and the NDF-only lobe's integral over the hemisphere of lights, 0.
#pragma once

namespace glimmer::ltc {

constexpr int kTableSize = 32;   // = FitSettings::size of tools/ltc_fit (the generated file checks it)
constexpr int kLayers = 6;
constexpr int kSpecularLayer = 0;     // + ndf
constexpr int kNdfOnlyLayer = 2;      // + ndf
constexpr int kMagnitudeLayer = 4;    // + ndf
extern const float kTableData[kLayers * kTableSize * kTableSize * 4];

// The four floats of entry (row, column) of `layer`.
inline const float* tableEntry(int layer, int row, int column) {
    return kTableData + ((layer * kTableSize + row) * kTableSize + column) * 4;
}

}  // namespace glimmer::ltc
