// Temporal anti-aliasing resolve (Karis 2014, "High Quality Temporal Supersampling"; Salvi 2016, "An Excursion
// in Temporal Supersampling"), with the glint radiance kept apart from the rectified history.
//
// The frame was rendered with a sub-pixel jitter of the projection (Halton 2,3). The history is reprojected with
// the depth of this pixel (the scene is static: camera motion only), read with a 5-tap Catmull-Rom filter (the
// sharpened resolve: a bilinear history blurs a little more every frame under motion) and blended with weight
// max(1 / (n + 1), feedback), n the history's sample count: a still camera gets the plain mean of its jittered
// frames until the exponential tail takes over.
//
// Rectification: the non-glint radiance (HDR minus the glint target) is clipped towards the mean of its 3x3
// neighbourhood, inside mean +- gamma * sigma in YCoCg (Salvi's variance clipping). Glints cannot go through that:
// a sparkle is one or two pixels outside the range of its neighbourhood and would be clipped away (or flicker as
// it is clipped in some frames and not others). The glint part therefore has its own history, bounded only by the
// brightest glint of the current 3x3 neighbourhood: a sparkle that is still there keeps its accumulated value, a
// sparkle that went out (new view angle, disocclusion) cannot leave a trail.
#include "common/bindings.glsl"
#include "image/taa_common.glsl"
layout(binding = UNIT_TAA_CURRENT) uniform sampler2D t_current;        // HDR radiance of this frame (glints included)
layout(binding = UNIT_TAA_GLINT_PART) uniform sampler2D t_currentGlint;   // the glint part of t_current
layout(binding = UNIT_TAA_DEPTH) uniform sampler2D t_depth;          // reversed-Z depth of this frame
layout(binding = UNIT_TAA_HISTORY_BASE) uniform sampler2D t_historyBase;    // rgb: resolved non-glint radiance, a: sample count
layout(binding = UNIT_TAA_HISTORY_GLINT) uniform sampler2D t_historyGlint;   // rgb: resolved glint radiance

layout(location = 0) uniform mat4 u_reprojection;   // previous unjittered viewProjection * inverse(this unjittered one)
layout(location = 1) uniform int u_reset;           // 1: no valid history (first frame, cut, resize, edit)
layout(location = 2) uniform float u_feedback;      // lower bound of the current frame's weight
layout(location = 3) uniform float u_clipGamma;     // variance clip box half-size in standard deviations
layout(location = 4) uniform int u_glintHistory;    // 0: glints are clipped with the rest (comparison only)
layout(location = 5) uniform float u_glintFeedback; // lower bound of the current frame's weight for glints
// A still camera (docs/image.md "A still camera"): u_stillIndex k > 0 on the k-th consecutive frame with the same
// unjittered view (0 while moving); u_stillFrames the jitter cycle's length, after which the history is complete
// and kept as it is.
layout(location = 8) uniform int u_stillIndex;
layout(location = 9) uniform int u_stillFrames;

in vec2 v_ndc;
layout(location = 0) out vec4 o_historyBase;
layout(location = 1) out vec4 o_historyGlint;
layout(location = 2) out vec4 o_resolved;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(t_current, 0);
    vec4 currentRgba = texelFetch(t_current, pixel, 0);
    vec3 current = currentRgba.rgb;
    vec3 currentGlint = u_glintHistory != 0 ? texelFetch(t_currentGlint, pixel, 0).rgb : vec3(0.0);
    vec3 currentBase = max(current - currentGlint, vec3(0.0));

    // Neighbourhood statistics of the non-glint radiance, and the brightest glint around.
    vec3 moment1 = vec3(0.0), moment2 = vec3(0.0), glintMax = vec3(0.0);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(pixel + ivec2(dx, dy), ivec2(0), size - 1);
            vec3 glint = u_glintHistory != 0 ? texelFetch(t_currentGlint, q, 0).rgb : vec3(0.0);
            vec3 base = rgbToYCoCg(max(texelFetch(t_current, q, 0).rgb - glint, vec3(0.0)));
            moment1 += base;
            moment2 += base * base;
            glintMax = max(glintMax, glint);
        }
    vec3 mean = moment1 / 9.0;
    vec3 sigma = sqrt(max(moment2 / 9.0 - mean * mean, vec3(0.0)));

    // Where this pixel's surface point was in the previous frame.
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
    vec4 previousClip = u_reprojection * vec4(ndc, texelFetch(t_depth, pixel, 0).r, 1.0);
    vec2 previousUv = previousClip.w > 0.0 ? previousClip.xy / previousClip.w * 0.5 + 0.5 : vec2(-1.0);
    bool valid = u_reset == 0 && all(greaterThanEqual(previousUv, vec2(0.0))) && all(lessThanEqual(previousUv, vec2(1.0)));

    float samples = 0.0;
    vec3 base = currentBase, glint = currentGlint;
    if (valid) {
        samples = texelFetch(t_historyBase, clamp(ivec2(previousUv * vec2(size)), ivec2(0), size - 1), 0).a;
        vec3 historyBase = sampleHistoryCatmullRom(t_historyBase, previousUv, vec2(size));
        vec3 historyGlint = max(textureLod(t_historyGlint, previousUv, 0.0).rgb, vec3(0.0));
        float weight, glintWeight;
        if (u_stillIndex > 0) {
            // Its own texel: the identity reprojection is exact only up to rounding, and a filtered fetch a hair
            // off the centre would blur the kept history a little more every frame.
            historyBase = texelFetch(t_historyBase, pixel, 0).rgb;
            historyGlint = max(texelFetch(t_historyGlint, pixel, 0).rgb, vec3(0.0));
            // The history is this pixel's own (the reprojection is the identity, nothing was disoccluded): the plain
            // mean of the still frames' jitter phases, the motion's history counting as one frame, with neither
            // clipping nor a weight floor; after a whole jitter cycle it is complete and stays as it is. With the
            // floor the history followed each jittered frame with weight u_feedback (u_glintFeedback for glints)
            // and a still camera's glinty pixels kept changing (issue 39).
            weight = u_stillIndex > u_stillFrames ? 0.0 : 1.0 / (min(samples, float(u_stillIndex)) + 1.0);
            glintWeight = weight;
        } else {
            weight = max(1.0 / (samples + 1.0), u_feedback);
            glintWeight = max(weight, u_glintFeedback);
            historyBase = yCoCgToRgb(clipToBox(rgbToYCoCg(historyBase), mean, u_clipGamma * sigma));
            historyGlint = min(historyGlint, glintMax);
        }
        base = mix(historyBase, currentBase, weight);
        glint = mix(historyGlint, currentGlint, glintWeight);
    }
    base = finiteOrZero(max(base, vec3(0.0)));
    glint = finiteOrZero(max(glint, vec3(0.0)));
    o_historyBase = vec4(base, min(samples + 1.0, u_stillIndex > 0 ? float(u_stillFrames + 1) : 1.0 / u_feedback));
    o_historyGlint = vec4(glint, 1.0);
    o_resolved = vec4(base + glint, currentRgba.a);   // alpha: coverage, as the lighting pass's
}
