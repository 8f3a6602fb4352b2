// Tone curves: scene-linear Rec.709 radiance (already exposed) -> display-linear [0, 1]. CPU mirror:
// engine/render/image/tone_curves.cpp (tests compare the two).
#ifndef GLIMMER_TONE_CURVES_GLSL
#define GLIMMER_TONE_CURVES_GLSL

const int TONEMAP_ACES = 0;
const int TONEMAP_NEUTRAL = 1;
const int TONEMAP_AGX = 2;

// Narkowicz 2015, "ACES Filmic Tone Mapping Curve": a rational fit of the ACES RRT+ODT (sRGB), per channel.
vec3 tonemapAces(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// Khronos PBR Neutral (Khronos 3D Commerce, 2024): identity below the compression start apart from a small
// toe offset, then hue-preserving compression of the peak channel towards 1 and a desaturation towards white.
vec3 tonemapNeutral(vec3 color) {
    const float compressionStart = 0.8 - 0.04;
    const float desaturation = 0.15;
    float lowest = min(color.r, min(color.g, color.b));
    float toe = lowest < 0.08 ? lowest - 6.25 * lowest * lowest : 0.04;
    color -= toe;
    float peak = max(color.r, max(color.g, color.b));
    if (peak < compressionStart) return clamp(color, 0.0, 1.0);
    float d = 1.0 - compressionStart;
    float newPeak = 1.0 - d * d / (peak + d - compressionStart);
    color *= newPeak / peak;
    float towardWhite = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return clamp(mix(color, vec3(newPeak), towardWhite), 0.0, 1.0);
}

// AgX (T. Sobotka 2022; the "minimal" form with a polynomial fit of its sigmoid, as used by Blender 4 and
// three.js): an inset into a wider primaries space, a log2 encoding over [-12.47, 4.03] EV around 0.18, a sigmoid,
// the outset back, and the 2.2 display power undone to display-linear.
vec3 tonemapAgx(vec3 color) {
    const mat3 inset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                            0.0784335999999992, 0.878468636469772, 0.0784336,
                            0.0792237451477643, 0.0791661274605434, 0.879142973793104);
    const mat3 outset = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
                             -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
                             -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
    const float minEv = -12.47393, maxEv = 4.026069;
    vec3 x = inset * max(color, vec3(0.0));
    x = clamp((log2(max(x, vec3(1e-10))) - minEv) / (maxEv - minEv), 0.0, 1.0);
    vec3 x2 = x * x, x4 = x2 * x2;
    x = 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
    x = outset * x;
    return clamp(pow(max(x, vec3(0.0)), vec3(2.2)), 0.0, 1.0);
}

vec3 applyToneCurve(int curve, vec3 x) {
    if (curve == TONEMAP_NEUTRAL) return tonemapNeutral(x);
    if (curve == TONEMAP_AGX) return tonemapAgx(x);
    return tonemapAces(x);
}

vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

#endif
