// Bloom, one step down the chain (Jimenez 2014, "Next Generation Post Processing in Call of Duty: Advanced
// Warfare", slides 143-153): 13 bilinear taps forming five overlapping 2x2-texel boxes (inner box weight 0.5,
// four corner boxes 0.125 each), a wide filter that does not alias or lose energy. On the first step the taps are
// weighted by 1 / (1 + luma) (the "Karis average", slide 168) so one extreme pixel cannot become a bright square.
// The target is half the size of the source; sampling clamps to the edge, so a constant image stays constant.
#include "common/bindings.glsl"
layout(binding = UNIT_BLOOM_SOURCE) uniform sampler2D t_source;
layout(location = 0) uniform vec2 u_sourceTexel;   // 1 / source size
layout(location = 1) uniform int u_karis;          // 1 on the first downsample

in vec2 v_ndc;
layout(location = 0) out vec4 o_color;

vec3 tap(vec2 uv, float dx, float dy) { return textureLod(t_source, uv + vec2(dx, dy) * u_sourceTexel, 0.0).rgb; }

float karisWeight(vec3 box) { return 1.0 / (1.0 + dot(box, vec3(0.2126, 0.7152, 0.0722))); }

vec3 finiteOrZero(vec3 c) { return any(isnan(c)) || any(isinf(c)) ? vec3(0.0) : c; }

void main() {
    vec2 uv = v_ndc * 0.5 + 0.5;   // the target pixel's centre = the centre of a 2x2 source block
    vec3 a = tap(uv, -2.0, 2.0), b = tap(uv, 0.0, 2.0), c = tap(uv, 2.0, 2.0);
    vec3 d = tap(uv, -2.0, 0.0), e = tap(uv, 0.0, 0.0), f = tap(uv, 2.0, 0.0);
    vec3 g = tap(uv, -2.0, -2.0), h = tap(uv, 0.0, -2.0), i = tap(uv, 2.0, -2.0);
    vec3 j = tap(uv, -1.0, 1.0), k = tap(uv, 1.0, 1.0), l = tap(uv, -1.0, -1.0), m = tap(uv, 1.0, -1.0);
    if (u_karis == 0) {
        vec3 inner = (j + k + l + m) * 0.25;
        vec3 corners = (a + b + d + e) + (b + c + e + f) + (d + e + g + h) + (e + f + h + i);
        o_color = vec4(finiteOrZero(inner * 0.5 + corners * (0.125 * 0.25)), 1.0);
        return;
    }
    // The same 13-tap weights (centre 0.125, edges 0.0625, corners 0.03125, inner 0.125 each), each tap also
    // weighted by 1 / (1 + luma) and the sum renormalised. Per tap rather than per box: a firefly under the centre
    // tap lies in all five boxes, so per-box weights would shrink together and let it through.
    vec3 sum = vec3(0.0);
    float weight = 0.0;
    vec3 taps[13] = vec3[13](a, b, c, d, e, f, g, h, i, j, k, l, m);
    const float filterWeights[13] = float[13](0.03125, 0.0625, 0.03125, 0.0625, 0.125, 0.0625, 0.03125, 0.0625,
                                              0.03125, 0.125, 0.125, 0.125, 0.125);
    for (int t = 0; t < 13; ++t) {
        float w = filterWeights[t] * karisWeight(taps[t]);
        sum += taps[t] * w;
        weight += w;
    }
    o_color = vec4(finiteOrZero(sum / weight), 1.0);
}
