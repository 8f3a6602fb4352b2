// Bloom, one step up the chain (Jimenez 2014, slide 162): a 3x3 tent (1 2 1 / 2 4 2 / 1 2 1) / 16 over the
// coarser level, its radius in texels of that level (bloom.radius), added to this level's downsampled image.
// The caller adds the result to the finer level (blend ONE, ONE), so the top of the chain holds the sum of every
// level; the tone-mapping pass divides by the level count (energy kept: a constant image gives the same constant).
#include "common/bindings.glsl"
layout(binding = UNIT_BLOOM_SOURCE) uniform sampler2D t_coarser;
layout(location = 0) uniform vec2 u_coarserTexel;   // 1 / coarser size
layout(location = 1) uniform float u_radius;

in vec2 v_ndc;
layout(location = 0) out vec4 o_color;

void main() {
    vec2 uv = v_ndc * 0.5 + 0.5;
    vec2 r = u_coarserTexel * u_radius;
    vec3 sum = textureLod(t_coarser, uv, 0.0).rgb * 4.0;
    sum += (textureLod(t_coarser, uv + vec2(-r.x, 0.0), 0.0).rgb + textureLod(t_coarser, uv + vec2(r.x, 0.0), 0.0).rgb +
            textureLod(t_coarser, uv + vec2(0.0, -r.y), 0.0).rgb + textureLod(t_coarser, uv + vec2(0.0, r.y), 0.0).rgb) * 2.0;
    sum += textureLod(t_coarser, uv + vec2(-r.x, -r.y), 0.0).rgb + textureLod(t_coarser, uv + vec2(r.x, -r.y), 0.0).rgb +
           textureLod(t_coarser, uv + vec2(-r.x, r.y), 0.0).rgb + textureLod(t_coarser, uv + vec2(r.x, r.y), 0.0).rgb;
    o_color = vec4(sum / 16.0, 1.0);
}
