/* glimmer-method
name:      deliot2023_smoothstep
title:     Deliot & Belcour 2023 with smoothstep angular blending (example user method)
citation:  Deliot & Belcour 2023, CGF 42(8), Sec. 3-6; Eq. 14's bilinear angular weights replaced by smoothstep weights (ours)
resources: deliot2023
converge:  log_density=40
param: log_density = 16 in [0, 50]: natural log of the microfacet density per unit UV area
param: microfacet_roughness = 0.005 in [0.001, 1] log: R, ratio of micro- to macro-roughness (lower = fewer, brighter glints)
param: density_randomization = 2 in [0, 10]: std. deviation of the per-vertex log density
param: screen_space_scale = 1.5 in [0.1, 10]: grid cell size in pixels across the footprint's minor axis
param: normalization = vertex in {vertex, footprint}: each vertex's count over its own facets (authors' code) or over the footprint's
param: angular_grid = projected in {projected, lobe}: Eq. 14 cell R wide in projected h (authors' code) or sqrt(R / D(n))
param: gate = soft in {soft, hard}: the authors' soft Bernoulli gate or Eq. 18's hard one
param: density_normal = irwin_hall in {irwin_hall, exact}: normal variate of the density randomization (exact: the authors')
param: max_ratio = 0 in [0, 1000]: clamp of D_P / D(n) (authors' code: 20); 0 = none
param: angular_blend = smoothstep in {bilinear, smoothstep}: weights of the 4 angular cells around h: Eq. 14's bilinear ones, or smoothstep per axis (ours)
map: log_density = ln(0.2 density_per_uv) - density_randomization^2/2
map: microfacet_roughness = (angular_size)^2 alpha^-2
map: density_randomization = 0
map: angular_grid = 1
map: gate = 1
*/
// An example of a user glint method (docs/user_methods.md): the built-in deliot2023 with one change, the
// weights of the four hemispherical-grid cells around the projected half vector (Eq. 14).
//
// Why: Eq. 14 blends the counts of the 4 angular cells bilinearly, so while the light or the view moves, a glint
// fades in and out over a whole cell width: the angular counterpart of the lerped LODs the paper replaces in
// space (Sec. 4, Fig. 2). Smoothstep weights s(f) = f^2 (3 - 2 f) per axis keep each cell's glints at nearly full
// intensity over more of the cell and shorten the cross-fade. They still sum to one (s(f) + s(1 - f) = 1), and
// each cell's count has the same binomial law, so the expectation E[D_P] = D is unchanged (Sec. 3): the method
// still converges to smooth and passes the furnace (glimmer check-method); what changes is the contrast of the
// glints (higher) and how abruptly they switch as h moves. angular_blend=bilinear gives deliot2023 exactly.
//
// Everything else is the built-in shader, included as a helper: its glintD is renamed out of the way and
// replaced by the one below (the same loop with other weights). The built-in's area-light and environment glints
// (Kneiphof & Klein 2024, 2025) come with it unchanged: they keep Eq. 14's bilinear weights. `resources: deliot2023` borrows the built-in's
// random-number texture (Sec. 6.3), which its helpers read.
#define glintD deliot2023GlintD
#include "glints/deliot2023/deliot2023.glsl"
#undef glintD

vec4 angularBlendWeights(vec2 f) {
    vec2 w = P_ANGULAR_BLEND > 0.5 ? f * f * (3.0 - 2.0 * f) : f;
    // textureGather order of the cells: a0 + (0, 1), a0 + (1, 1), a0 + (1, 0), a0.
    return vec4((1.0 - w.x) * w.y, w.x * w.y, w.x * (1.0 - w.y), (1.0 - w.x) * (1.0 - w.y));
}

float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    g_deliotLightCalls += 1;
    // The built-in's success probability for this light (Kneiphof & Klein 2024's from the light's solid angle, or
    // Eq. 4's p = R D(h) / D(n) with probability=db23, which this file leaves at the built-in's default).
    float p = deliotProbability(px, s, h, g_glintLight.ndfIntegral);
    if (!(p > 0.0)) return 0.0;
    // Eq. 14's grid of projected half vectors; the weights are the one change (angularBlendWeights).
    vec2 q = h.xy / px.angularCellSize - 0.5;
    vec2 qBase = floor(q);
    ivec2 a0 = ivec2(qBase);
    vec4 angularWeight = angularBlendWeights(q - qBase);
    float logMiss = deliotLogMiss(p);
    float count = 0.0;
    for (int v = 0; v < glintLoopCount(DELIOT_VERTICES); ++v) {
        // Eq. 10 + 18: the vertex's share of the footprint's facets, one gated binomial draw per angular cell.
        DeliotBinomialLaw law = deliotBinomialLaw(px.trials[v], p, logMiss, px.softGate);
        uvec4 packedPairs = deliotNoiseGather(px.texel[v], a0);
        float vertexCount = 0.0;
        for (int a = 0; a < 4; ++a) {
            vec2 rnd = deliotUnpackNoise(packedPairs[a]);
            vertexCount += angularWeight[a] * deliotDrawBinomial(law, rnd.x, rnd.y);
        }
        g_deliotEvaluations += 4;
        count += px.countWeight[v] * vertexCount;
    }
    // Eq. 3-4: D_P = D(h) / p * count / N (the / N is in countWeight).
    return D_smooth(h, s.alpha, s.ndf) / p * count;
}
