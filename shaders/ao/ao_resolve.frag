// Ambient-occlusion resolve: the spatial denoiser of GTAO (Jimenez et al. 2016, Sec. 4: a 4 x 4 depth-aware filter
// whose footprint holds each of the 4 x 4 interleaved slice rotations once), the baked sky visibility
// (sky_visibility.glsl), and the multi-bounce fit of Sec. 5. Writes the factor the lighting pass multiplies the
// environment / ambient term by (rgb, coloured by multi-bounce) and the combined visibility (a, --aov ao).
//
// Combination: product of the screen-space term (near field, within ao.radius) and the sky term (far field, the
// probe grid's resolution and beyond). They mostly see different occluders; min() would drop the contact
// darkening of creases inside the arcades, where the sky term is already the smaller one. An occluder that both
// see (between the grid's cell size and the radius) is counted twice (docs/ambient_occlusion.md).
#include "common/bindings.glsl"
#include "common/frame.glsl"
#include "ao/sky_visibility.glsl"
#include "common/plane_aware_upsample.glsl"

layout(binding = UNIT_AO_DEPTH) uniform sampler2D g_depth;
layout(binding = UNIT_AO_NORMAL) uniform sampler2D g_normalAlpha;
layout(binding = UNIT_AO_RAW) uniform sampler2D u_rawVisibility;
layout(binding = UNIT_AO_BASE_COLOR) uniform sampler2D g_baseColorMask;
layout(binding = UNIT_AO_TANGENT_METALLIC) uniform sampler2D g_tangentMetallic;
// x: 1 screen-space term on, y: 1 denoise, z: power (intensity), w: 1 multi-bounce
layout(location = 0) uniform vec4 u_resolve;
layout(location = 1) uniform mat4 u_inverseProjection;
// G-buffer pixels per texel (1, or 2 at ao.half_res: each texel is resolved at its sample pixel and the denoiser
// runs over the 4 x 4 neighbouring texels, 8 x 8 pixels)
layout(location = 5) uniform int u_step;

layout(location = 0) out vec4 o_occlusion;

float viewDepthOf(float d) {
    vec4 p = u_inverseProjection * vec4(0.0, 0.0, d, 1.0);
    return -p.z / p.w;
}

// Sec. 5: visibility with interreflections from a cubic fit in the visibility x and the albedo rho.
vec3 multiBounce(float x, vec3 rho) {
    vec3 a = 2.0404 * rho - 0.3324;
    vec3 b = -4.7951 * rho + 0.6417;
    vec3 c = 2.7552 * rho + 0.6903;
    return max(vec3(x), ((x * a + b) * x + c) * x);
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    ivec2 pixel = reducedSamplePixel(texel, u_step, u_viewport.xy);
    float depth = texelFetch(g_depth, pixel, 0).r;
    if (depth <= 0.0) { o_occlusion = vec4(1.0); return; }
    vec3 normal = normalize(texelFetch(g_normalAlpha, pixel, 0).xyz);

    float screen = 1.0;
    if (u_resolve.x > 0.5) {
        screen = texelFetch(u_rawVisibility, texel, 0).r;
        if (u_resolve.y > 0.5) {
            // 4 x 4 taps (offsets -2..1): one of each slice rotation. Weight: same surface, i.e. relative view depth
            // within 5% (depth only: a normal test doubled the fetches, and llvmpipe pays per fetch); the centre
            // always counts.
            ivec2 lastTexel = textureSize(u_rawVisibility, 0) - 1;
            float z = viewDepthOf(depth);
            float sum = 0.0, weights = 0.0;
            for (int dy = -2; dy <= 1; ++dy)
                for (int dx = -2; dx <= 1; ++dx) {
                    ivec2 q = clamp(texel + ivec2(dx, dy), ivec2(0), lastTexel);
                    float dq = texelFetch(g_depth, reducedSamplePixel(q, u_step, u_viewport.xy), 0).r;
                    if (dq <= 0.0) continue;
                    float depthWeight = clamp(1.0 - abs(viewDepthOf(dq) - z) / (0.05 * z), 0.0, 1.0);
                    float w = depthWeight + (q == texel ? 1e-3 : 0.0);
                    sum += w * texelFetch(u_rawVisibility, q, 0).r;
                    weights += w;
                }
            screen = sum / weights;
        }
    }
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(u_viewport.xy) * 2.0 - 1.0;
    vec4 world = u_inverseViewProjection * vec4(ndc, depth, 1.0);
    float visibility = pow(clamp(screen * skyVisibility(world.xyz / world.w, normal), 0.0, 1.0), u_resolve.z);
    // At ao.half_res the multi-bounce colour is that of the sample pixel's albedo, which the lighting pass then
    // interpolates with the visibility (docs/ambient_occlusion.md#half-resolution-aohalf_res).
    vec3 albedo = (1.0 - texelFetch(g_tangentMetallic, pixel, 0).w) * texelFetch(g_baseColorMask, pixel, 0).rgb;
    vec3 factor = u_resolve.w > 0.5 ? min(multiBounce(visibility, albedo), vec3(1.0)) : vec3(visibility);
    o_occlusion = vec4(factor, visibility);
}
