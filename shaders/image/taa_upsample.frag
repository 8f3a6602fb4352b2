// Temporal anti-aliasing with upsampling (TAAU): the frame was rendered at the internal resolution with a sub-pixel
// jitter (internal-pixel units) and this pass resolves it directly to the output resolution, where the history
// lives. The design follows Karis 2014 ("High Quality Temporal Supersampling": the current frame is reconstructed
// at the output pixel from the jittered samples around it with a Blackman-Harris-like kernel, and the kernel's
// weight says how much the new frame may contribute) and AMD FSR 2's description of the same steps (upsample the
// current samples, weight by sample-to-pixel distance, accumulate with that confidence). The rest is the plain
// resolve's (taa_resolve.frag): depth reprojection with the unjittered matrices, a Catmull-Rom history fetch,
// variance clipping in YCoCg (Salvi 2016) of the non-glint radiance, and the glint part kept apart from the clip.
//
// Current frame. Internal pixel q was shaded at its centre q + 0.5 of the jittered image, which is the point of
// the unjittered image at s_q = q + 0.5 - jitter (internal-pixel units; lighting.frag's unjitterGlintFootprint
// uses the same convention). The output pixel centre p gathers the 3 x 3 internal samples around the nearest
// one with w_q = exp(-2.29 |s_q - p|^2 / width^2), distances in output pixels: Karis' Gaussian fit of a
// Blackman-Harris window of width 3.3 when width is 1. Accumulation uses u_kernelWidth (output pixels); a pixel
// without history (reset, disocclusion, off-screen) is filled with width = one internal pixel instead, so the first
// frame after a cut is a smooth upscale rather than nearest-neighbour blocks.
//
// Accumulation: the history's alpha counts the frames it holds, here fractional: each frame adds its confidence
// c = min(sum w_q, 1), and the new frame's weight is c / min(n + c, 1 / feedback) (the weighted running mean; with
// c = 1 the plain resolve's max(1 / (n + 1), feedback)). An output pixel that no sample came near this frame keeps
// its history.
#include "common/bindings.glsl"
#include "image/taa_common.glsl"
layout(binding = UNIT_TAA_CURRENT) uniform sampler2D t_current;        // HDR radiance, internal size (glints included)
layout(binding = UNIT_TAA_GLINT_PART) uniform sampler2D t_currentGlint;   // the glint part of t_current
layout(binding = UNIT_TAA_DEPTH) uniform sampler2D t_depth;          // reversed-Z depth, internal size
layout(binding = UNIT_TAA_HISTORY_BASE) uniform sampler2D t_historyBase;    // output size; rgb: non-glint, a: frames held
layout(binding = UNIT_TAA_HISTORY_GLINT) uniform sampler2D t_historyGlint;   // output size; rgb: glint radiance

layout(location = 0) uniform mat4 u_reprojection;   // previous unjittered viewProjection * inverse(this unjittered one)
layout(location = 1) uniform int u_reset;           // 1: no valid history
layout(location = 2) uniform float u_feedback;      // lower bound of the current frame's weight (at confidence 1)
layout(location = 3) uniform float u_clipGamma;     // variance clip box half-size in standard deviations
layout(location = 4) uniform int u_glintHistory;    // 0: glints are clipped with the rest (comparison only)
layout(location = 5) uniform float u_glintFeedback; // lower bound of the current frame's weight for glints
layout(location = 6) uniform vec2 u_jitter;         // this frame's jitter, internal pixels
layout(location = 7) uniform float u_kernelWidth;   // reconstruction kernel width for accumulation, output pixels
// A still camera, as in taa_resolve.frag: the k-th still frame (0: moving) and the jitter cycle's length.
layout(location = 8) uniform int u_stillIndex;
layout(location = 9) uniform int u_stillFrames;

in vec2 v_ndc;
layout(location = 0) out vec4 o_historyBase;
layout(location = 1) out vec4 o_historyGlint;
layout(location = 2) out vec4 o_resolved;

void main() {
    ivec2 outputSize = textureSize(t_historyBase, 0);
    ivec2 inputSize = textureSize(t_current, 0);
    vec2 outputFromInput = vec2(outputSize) / vec2(inputSize);   // the upscale ratio per axis
    vec2 position = gl_FragCoord.xy / outputFromInput;            // this pixel's centre in internal pixels
    ivec2 nearest = clamp(ivec2(floor(position + u_jitter)), ivec2(0), inputSize - 1);

    // Where this pixel's surface point was in the previous frame (depth of the nearest sample): decides the kernel.
    vec2 ndc = gl_FragCoord.xy / vec2(outputSize) * 2.0 - 1.0;
    vec4 previousClip = u_reprojection * vec4(ndc, texelFetch(t_depth, nearest, 0).r, 1.0);
    vec2 previousUv = previousClip.w > 0.0 ? previousClip.xy / previousClip.w * 0.5 + 0.5 : vec2(-1.0);
    bool valid = u_reset == 0 && all(greaterThanEqual(previousUv, vec2(0.0))) && all(lessThanEqual(previousUv, vec2(1.0)));
    float width = valid ? u_kernelWidth : max(u_kernelWidth, max(outputFromInput.x, outputFromInput.y));
    float falloff = -2.29 / (width * width);

    vec3 moment1 = vec3(0.0), moment2 = vec3(0.0), glintMax = vec3(0.0);
    vec3 sumBase = vec3(0.0), sumGlint = vec3(0.0);
    float weight = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(nearest + ivec2(dx, dy), ivec2(0), inputSize - 1);
            vec3 glint = u_glintHistory != 0 ? texelFetch(t_currentGlint, q, 0).rgb : vec3(0.0);
            vec3 base = max(texelFetch(t_current, q, 0).rgb - glint, vec3(0.0));
            vec3 baseYCoCg = rgbToYCoCg(base);
            moment1 += baseYCoCg;
            moment2 += baseYCoCg * baseYCoCg;
            glintMax = max(glintMax, glint);
            vec2 offset = (vec2(q) + 0.5 - u_jitter - position) * outputFromInput;   // output pixels
            float w = exp(falloff * dot(offset, offset));
            sumBase += w * base;
            sumGlint += w * glint;
            weight += w;
        }
    vec3 mean = moment1 / 9.0;
    vec3 sigma = sqrt(max(moment2 / 9.0 - mean * mean, vec3(0.0)));
    float confidence = min(weight, 1.0);
    // The nearest sample's weight is at least exp(-2.29 * 0.5 * ratio^2 / width^2) > 0: no division by zero.
    vec3 currentBase = sumBase / max(weight, 1e-30), currentGlint = sumGlint / max(weight, 1e-30);

    float frames = confidence, maxFrames = u_stillIndex > 0 ? float(u_stillFrames + 1) : 1.0 / u_feedback;
    vec3 base = currentBase, glint = currentGlint;
    if (valid) {
        frames = texelFetch(t_historyBase, clamp(ivec2(previousUv * vec2(outputSize)), ivec2(0), outputSize - 1), 0).a;
        vec3 historyBase = sampleHistoryCatmullRom(t_historyBase, previousUv, vec2(outputSize));
        vec3 historyGlint = max(textureLod(t_historyGlint, previousUv, 0.0).rgb, vec3(0.0));
        float blend, glintBlend;
        if (u_stillIndex > 0) {
            // Its own texel, not a filtered fetch at the (rounded) identity reprojection (taa_resolve.frag).
            historyBase = texelFetch(t_historyBase, ivec2(gl_FragCoord.xy), 0).rgb;
            historyGlint = max(texelFetch(t_historyGlint, ivec2(gl_FragCoord.xy), 0).rgb, vec3(0.0));
            // Still: the weighted mean of the still frames (the motion's history counting as one frame), complete and
            // kept after a whole jitter cycle (taa_resolve.frag).
            float held = min(frames, float(u_stillIndex));
            blend = u_stillIndex > u_stillFrames ? 0.0 : confidence / max(held + confidence, 1e-6);
            glintBlend = blend;
        } else {
            blend = confidence / max(min(frames + confidence, maxFrames), 1e-6);
            glintBlend = max(blend, u_glintFeedback * confidence);
            historyBase = yCoCgToRgb(clipToBox(rgbToYCoCg(historyBase), mean, u_clipGamma * sigma));
            historyGlint = min(historyGlint, glintMax);
        }
        base = mix(historyBase, currentBase, blend);
        glint = mix(historyGlint, currentGlint, glintBlend);
        frames = min(frames + confidence, maxFrames);
    }
    base = finiteOrZero(max(base, vec3(0.0)));
    glint = finiteOrZero(max(glint, vec3(0.0)));
    o_historyBase = vec4(base, frames);
    o_historyGlint = vec4(glint, 1.0);
    o_resolved = vec4(base + glint, texelFetch(t_current, nearest, 0).a);   // alpha: coverage of the nearest sample
}
