// Ground-truth ambient occlusion (GTAO), Jimenez, Wu, Pesce and Jarabo 2016, "Practical Real-Time Strategies
// for Accurate Indirect Occlusion", Sec. 4: the cosine-weighted visibility of the hemisphere around the shading
// normal, integrated in `slices` planes that contain the view vector. In each slice a horizon search over the
// depth buffer finds the two horizon angles h1 <= 0 <= h2, which are clamped to the hemisphere of the normal
// projected into the slice, and the inner integral over the visible arc is solved in closed form (Sec. 4, the
// expression a-hat(h1, h2, n) for the cosine-weighted arc), weighted by the projected normal's length.
// (No copy of the paper is in ../shared/papers: section numbers are those of the Activision technical report as
// recalled, the formulas are derived again in docs/ambient_occlusion.md.)
//
// Deviations (docs/ambient_occlusion.md):
//  - Several slices per pixel instead of the paper's one slice per frame with temporal reprojection (Sec. 4's spatio-temporal
//    denoising):
//    the renderer has no history buffer and offline renders must be complete in one frame. Slice angles and step
//    offsets still follow a 4 x 4 interleaved pattern that the spatial 4 x 4 denoiser (ao_resolve.frag) averages out.
//  - The result is the ratio of the visible to the unoccluded integral of the same slices, not their mean
//    divided by pi: with few slices the mean of an unoccluded oblique surface scatters around 1, the ratio is 1
//    exactly (nothing occludes: nothing changes) and converges to the same value.
//  - Occluders fade out linearly over the last (1 - falloff) of the radius, so the search radius has no hard rim.
//  - No multi-bounce here: the resolve pass applies Sec. 5's fit with the surface albedo.
#include "common/bindings.glsl"
#include "common/frame.glsl"
#include "common/constants.glsl"
#include "common/plane_aware_upsample.glsl"
const float HALF_PI = 1.57079632679489661923;

layout(binding = UNIT_AO_DEPTH) uniform sampler2D g_depth;
layout(binding = UNIT_AO_NORMAL) uniform sampler2D g_normalAlpha;
layout(location = 0) uniform mat4 u_inverseProjection;
layout(location = 1) uniform vec4 u_gtao;   // x radius (m), y slices, z steps per side, w falloff start (fraction)
// G-buffer pixels per target texel: 1, or 2 at ao.half_res (the texel is computed at its sample pixel,
// common/plane_aware_upsample.glsl, and the lighting pass interpolates the resolved factor)
layout(location = 2) uniform int u_step;

layout(location = 0) out float o_visibility;

vec3 viewPosition(vec2 pixelCentre, float depth) {
    vec2 ndc = pixelCentre / vec2(u_viewport.xy) * 2.0 - 1.0;
    vec4 p = u_inverseProjection * vec4(ndc, depth, 1.0);
    return p.xyz / p.w;
}

// 4 x 4 interleaved values in [0, 1): a Bayer matrix for the slice rotation, its transpose for the step offset.
float bayer4(ivec2 p) {
    const float m[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0, 15.0, 7.0, 13.0, 5.0);
    return (m[(p.y & 3) * 4 + (p.x & 3)] + 0.5) / 16.0;
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    ivec2 pixel = reducedSamplePixel(texel, u_step, u_viewport.xy);
    float depth = texelFetch(g_depth, pixel, 0).r;
    if (depth <= 0.0) { o_visibility = 1.0; return; }   // sky
    vec3 P = viewPosition(vec2(pixel) + 0.5, depth);
    vec3 V = normalize(-P);
    vec3 N = normalize(mat3(u_view) * texelFetch(g_normalAlpha, pixel, 0).xyz);
    if (dot(N, V) < 0.0) N = -N;   // a back face seen through a two-sided material: its visible side

    float radius = u_gtao.x;
    int slices = int(u_gtao.y), steps = int(u_gtao.z);
    float falloffStart = u_gtao.w;
    // The radius in pixels at this depth (projection scale = half the viewport height times P[1][1]).
    float radiusPixels = radius * 0.5 * float(u_viewport.y) * u_projection[1][1] / max(-P.z, 1e-4);
    if (radiusPixels < 1.0) { o_visibility = 1.0; return; }
    radiusPixels = min(radiusPixels, 0.5 * float(u_viewport.y));   // bounds the cost (and the cache misses) up close

    // Interleaved per target texel, so that the resolve's 4 x 4 texels hold each rotation once at either step.
    float sliceOffset = bayer4(texel), stepOffset = bayer4(texel.yx);
    float visible = 0.0, unoccluded = 0.0;
    // Both loops run at least once (ao.slices, ao.steps >= 1) and test at their bottom: llvmpipe runs a top-tested
    // loop's body once more with every pixel masked off (lights/ltc.glsl ltcLoopCount). `continue` goes to the test.
    int s = 0;
    do {
        float phi = PI * (float(s) + sliceOffset) / float(slices);
        vec2 omega = vec2(cos(phi), sin(phi));
        // The slice plane holds V and the screen direction; its angles are measured from V towards +omega.
        vec3 direction = vec3(omega, 0.0);
        vec3 orthoDirection = normalize(direction - dot(direction, V) * V);
        vec3 axis = cross(orthoDirection, V);
        vec3 projectedNormal = N - axis * dot(N, axis);
        float projectedLength = length(projectedNormal);
        if (projectedLength < 1e-4) continue;
        float cosN = clamp(dot(projectedNormal, V) / projectedLength, -1.0, 1.0);
        float n = sign(dot(projectedNormal, orthoDirection)) * acos(cosN);   // normal angle in the slice

        // Horizon search (Sec. 4): the largest cosine to V of the samples on each side, starting from the
        // tangent plane (cos(n +- pi/2)); samples beyond the radius fade to it.
        float lowPlus = cos(n + HALF_PI), lowMinus = cos(n - HALF_PI);
        float cosPlus = lowPlus, cosMinus = lowMinus;
        int j = 0;
        do {
            float t = (float(j) + stepOffset) / float(steps);
            float distancePixels = max(t * t * radiusPixels, float(j) + 1.0);   // denser near the centre
            for (int side = 0; side < 2; ++side) {
                vec2 samplePixel = vec2(pixel) + 0.5 + (side == 0 ? omega : -omega) * distancePixels;
                if (any(lessThan(samplePixel, vec2(0.5))) || any(greaterThan(samplePixel, vec2(u_viewport.xy) - 0.5)))
                    continue;
                // Depth filtered bilinearly at the exact sample position (the pass binds a linear sampler): NDC depth is
                // linear in screen space across a plane, so the sample stays on the slice line and on the surface.
                // A texel centre off the line would see a plane's own tangent directions out of the slice, whose
                // angle to V lies above the slice's horizon, and darken every plane (docs/measurements.md).
                float sampleDepth = texture(g_depth, samplePixel / vec2(u_viewport.xy)).r;
                if (sampleDepth <= 0.0) continue;
                vec3 delta = viewPosition(samplePixel, sampleDepth) - P;
                float len = length(delta);
                if (len < 1e-5) continue;
                float weight = clamp((radius - len) / (radius * (1.0 - falloffStart)), 0.0, 1.0);
                float c = dot(delta / len, V);
                if (side == 0) cosPlus = max(cosPlus, mix(lowPlus, c, weight));
                else cosMinus = max(cosMinus, mix(lowMinus, c, weight));
            }
        } while (++j < steps);
        float h1 = -acos(clamp(cosMinus, -1.0, 1.0)), h2 = acos(clamp(cosPlus, -1.0, 1.0));
        h1 = n + max(h1 - n, -HALF_PI);
        h2 = n + min(h2 - n, HALF_PI);
        // Sec. 4: a-hat = 1/4 (-cos(2 h1 - n) + cos n + 2 h1 sin n) + 1/4 (-cos(2 h2 - n) + cos n + 2 h2 sin n);
        // with h1 = n - pi/2, h2 = n + pi/2 (nothing occludes) it is cos n + n sin n.
        float cosn = cos(n), sinn = sin(n);
        float arc = 0.25 * (-cos(2.0 * h1 - n) + cosn + 2.0 * h1 * sinn) + 0.25 * (-cos(2.0 * h2 - n) + cosn + 2.0 * h2 * sinn);
        visible += projectedLength * arc;
        unoccluded += projectedLength * (cosn + n * sinn);
    } while (++s < slices);
    o_visibility = unoccluded > 1e-6 ? clamp(visible / unoccluded, 0.0, 1.0) : 1.0;
}
