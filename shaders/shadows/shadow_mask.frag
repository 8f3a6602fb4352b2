// Shadow mask (render/shadows/shadow_mask_pass.h): lightVisibility (shadows/shadows.glsl) of the four shadowed lights
// of mask layer u_layer (slots 4 x u_layer .. + 3) at one
// G-buffer pixel per mask texel (every second pixel in x and y at shadow.half_res=1), with the same position,
// normal and light direction as the lighting pass, so a sample pixel's visibility is what the lighting pass would
// compute there. Sky pixels and missing lights: 1.
#include "common/bindings.glsl"
#include "common/frame.glsl"
#include "common/light_incidence.glsl"
#include "shadows/shadows.glsl"

layout(binding = UNIT_GBUFFER_NORMAL_ALPHA) uniform sampler2D g_normalAlpha;
layout(binding = UNIT_GBUFFER_DEPTH) uniform sampler2D g_depth;

layout(location = 0) uniform int u_layer;

// The filters of this layer's four slots (SHADOW_FILTER_*), compiled in by render/shadows/shadow_mask_pass.cpp so
// that each slot runs its own light's lookup only; without the define every slot decides at run time.
#ifndef SHADOW_MASK_FILTERS
#define SHADOW_MASK_FILTERS ivec4(SHADOW_FILTER_ANY)
#endif

out vec4 o_visibility;

float slotVisibility(int slotFilter, int channel, vec3 position, vec3 n) {
    if (slotFilter == SHADOW_FILTER_NONE || 4 * u_layer + channel >= u_shadowMask.y) return 1.0;
    int i = u_shadowSlotLights[u_layer][channel];
    vec3 towardLight, irradiance;
    lightIncidence(u_lights[i], position, towardLight, irradiance);
    // Size: radius of a point or spot light, of a disk of an area light's area (render/gpu_scene.cpp).
    float size = u_lights[i].vectorType.w > 0.5 ? u_lights[i].spotOffsetRange.z : 0.0;
    return lightVisibility(slotFilter, i, u_lights[i].vectorType.xyz, size, position, n, towardLight);
}

void main() {
    ivec2 pixel = shadowMaskPixel(ivec2(gl_FragCoord.xy), u_viewport.xy);
    float depth = texelFetch(g_depth, pixel, 0).r;
    vec4 visibility = vec4(1.0);
    if (depth > 0.0) {
        vec3 position = worldPosition(pixel, depth);
        vec3 n = normalize(texelFetch(g_normalAlpha, pixel, 0).xyz);
        // One call per channel with its constant slotFilter (a loop over a constant array might stay a loop).
        const ivec4 filters = SHADOW_MASK_FILTERS;
        visibility = vec4(slotVisibility(filters.x, 0, position, n), slotVisibility(filters.y, 1, position, n),
                          slotVisibility(filters.z, 2, position, n), slotVisibility(filters.w, 3, position, n));
    }
    o_visibility = visibility;
}
