// Visibility of a light from a surface point, from the shadow maps of render/shadows/shadow_maps.h (fitted on the CPU,
// rendered by render/shadows/shadow_map_pass.cpp). Every shadow is a set of views, each one layer of a 2D depth
// array (reversed Z: 1 nearest the light): the sun's cascades (orthographic) in s_shadowSun, the six cube faces
// of a point light and the single view of a spot light (perspective) in s_shadowLocal.
// Bias (docs/shadows.md): the receiver moves along its normal by normal_bias texels x sin(normal, light) (Holbert
// 2011, "normal offset shadows"; it gives a depth margin of normal_bias texels x tan) and towards the light by
// bias texels; the casters carry a slope-scaled depth offset (glPolygonOffset, shadow.slope_bias).
// Filter: 4 x 4 hardware bilinear compares spread evenly over +-radius texels (percentage-closer filtering,
// Reeves et al. 1987); at radius 1.5 the taps are one texel apart and their tents overlap into one smooth kernel.
// Lights with a size (area lights, point and spot lights with a radius) cast soft shadows: percentage-closer soft
// shadows (Fernando 2005) in their perspective views: a blocker search, then a penumbra from the light's size
// w = size (d_receiver - d_blocker) / d_blocker, filtered by 6 x 6 compares over it (shadowPcssLocal).
#include "common/bindings.glsl"
#include "common/plane_aware_upsample.glsl"

#define MAX_SHADOW_VIEWS 64     // render/shadows/shadow_maps.h kMaxShadowViews
#define MAX_SHADOW_LIGHTS 64    // kMaxShadowLights
#define MAX_SHADOW_SLOTS 12     // kMaxShadowSlots: shadowed lights, 4 per layer of the shadow mask
const int SHADOW_NONE = 0;
const int SHADOW_CASCADES = 1;
const int SHADOW_CUBE = 2;
const int SHADOW_SPOT = 3;
// How a shadow-mask slot filters its light (render/shadows/shadow_maps.h ShadowFilter): the shadow mask's program is
// compiled for the filters of its layer's four slots (render/shadows/shadow_mask_pass.cpp), since llvmpipe runs both
// sides of every branch: a generic program paid for the cascades', the PCF's and the soft shadows' lookups at every
// light. SHADOW_FILTER_ANY decides from the light's record at run time (every path present).
const int SHADOW_FILTER_ANY = -1;
const int SHADOW_FILTER_NONE = 0;       // an empty slot
const int SHADOW_FILTER_CASCADES = 1;   // the sun: 4 x 4 PCF in its cascade
const int SHADOW_FILTER_PCF = 2;        // a point or spot light without a size: 4 x 4 PCF in its view
const int SHADOW_FILTER_PCSS = 3;       // a light with a size: percentage-closer soft shadows in its view

layout(std140, binding = BINDING_SHADOWS) uniform ShadowBlock {
    mat4 u_shadowViews[MAX_SHADOW_VIEWS];      // world -> clip of each view
    vec4 u_shadowViewInfo[MAX_SHADOW_VIEWS];   // x texel size (m; perspective: per m of depth), y layer, z perspective, w array
    ivec4 u_shadowLights[MAX_SHADOW_LIGHTS];   // per light: x kind, y first view, z view count, w mask slot (-1: none)
    vec4 u_shadowFilter;                       // x PCF radius, y normal bias, z depth bias (texels), w 1 when on
    vec4 u_shadowMapSizes;                     // x 1 / sun size, y 1 / local size, z sun size, w local size
    ivec4 u_shadowMask;                        // x G-buffer pixels per mask texel (1, 2), y slots, z mask layers
    ivec4 u_shadowSlotLights[MAX_SHADOW_SLOTS / 4];   // the light of each slot (slot = 4 x layer + channel)
    vec4 u_shadowSoft;                         // x near plane of the local views (m), y widest penumbra (texels)
};
layout(binding = UNIT_SHADOW_SUN) uniform sampler2DArrayShadow s_shadowSun;
layout(binding = UNIT_SHADOW_LOCAL) uniform sampler2DArrayShadow s_shadowLocal;
// The same depths without comparison (a sampler object on its own unit), for the soft shadows' blocker search.
layout(binding = UNIT_SHADOW_LOCAL_DEPTH) uniform sampler2DArray s_shadowLocalDepth;
layout(binding = UNIT_SHADOW_MASK) uniform sampler2DArray s_shadowMask;

// Tap offsets of the PCF kernel in texels for `radius`; the reach is radius + 1 texel (the bilinear tent).
vec2 shadowTapOffset(int i, int j, float radius) { return (vec2(i, j) - 1.5) * (radius * (2.0 / 3.0)); }

// llvmpipe runs both sides of every branch (masked), so the lookups are written branch-free: one kernel per array
// and light, no early out.
float shadowPcfSun(vec2 uv, float layer, float depth, float texel, float radius) {
    float sum = 0.0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            sum += texture(s_shadowSun, vec4(uv + shadowTapOffset(i, j, radius) * texel, layer, depth));
    return sum * (1.0 / 16.0);
}
float shadowPcfLocal(vec2 uv, float layer, float depth, float texel, float radius) {
    float sum = 0.0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            sum += texture(s_shadowLocal, vec4(uv + shadowTapOffset(i, j, radius) * texel, layer, depth));
    return sum * (1.0 / 16.0);
}

// Percentage-closer soft shadows (Fernando 2005, "Percentage-Closer Soft Shadows") in a perspective view of a light
// of radius `size` (m) whose view depth at the receiver is `depth` (m): the map's depths are reversed and infinite
// (stored near / depth). 1. Blocker search over the penumbra a blocker half-way to the light would cast,
// size / (depth texelWorld) texels; 2. the mean blocker depth gives the penumbra w = size (depth - blocker) /
// blocker, in texels w / (depth texelWorld); 3. 6 x 6 bilinear compares over it (at least the PCF radius).
// Deviation: the widest penumbra is clamped (u_shadowSoft.y texels) so that the kernel stays within the face's guard.
float shadowPcssLocal(vec2 uv, float layer, float ndcDepth, float depth, float texelWorld, float size, float radius) {
    float texel = u_shadowMapSizes.y;
    float widest = u_shadowSoft.y;
    // The tap grids turn by a per-pixel angle (an integer hash of the pixel): a wide kernel's 6 x 6 taps are
    // several texels apart, and an unturned grid draws concentric bands across a penumbra; turned, they become
    // fine noise.
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    uint hash = (pixel.x * 1973u + pixel.y * 9277u + 26699u) | 1u;
    hash ^= hash >> 13u;
    hash *= 0x5bd1e995u;
    hash ^= hash >> 15u;
    float angle = float(hash & 0xffffu) * (6.2831853 / 65536.0);
    mat2 turn = mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
    float search = clamp(size / max(depth * texelWorld, 1e-9), radius, widest);
    float blockers = 0.0, blockerSum = 0.0;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            vec2 offset = turn * shadowTapOffset(i, j, search);
            float stored = textureLod(s_shadowLocalDepth, vec3(uv + offset * texel, layer), 0.0).r;
            bool blocks = stored > ndcDepth;   // reversed: nearer the light
            blockers += blocks ? 1.0 : 0.0;
            blockerSum += blocks ? u_shadowSoft.x / max(stored, 1e-9) : 0.0;
        }
    float blockerDepth = blockers > 0.0 ? blockerSum / blockers : depth;
    float penumbra = size * max(depth - blockerDepth, 0.0) / max(blockerDepth, 1e-6);
    float kernel = clamp(penumbra / max(depth * texelWorld, 1e-9), radius, widest);
    float sum = 0.0;
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i)
            sum += texture(s_shadowLocal, vec4(uv + turn * ((vec2(i, j) - 2.5) * (kernel * 0.4)) * texel, layer, ndcDepth));
    return blockers > 0.0 ? sum * (1.0 / 36.0) : 1.0;
}

// The receiver point moved by the biases for a view whose texel measures `texel` metres here.
vec3 shadowReceiver(vec3 position, vec3 normal, vec3 towardLight, float texel) {
    float cosTheta = clamp(dot(normal, towardLight), 0.0, 1.0);
    float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
    return position + normal * (texel * u_shadowFilter.y * sinTheta) + towardLight * (texel * u_shadowFilter.z);
}

// Visibility in [0, 1] of light `index` (its vector: position of a point light) at `position` with unit
// `normal`; 1 for lights without a shadow map. `size`: the light's radius in metres (0: a point; soft shadows).
// `kind`: SHADOW_FILTER_* of the light, a constant where the caller knows it (the branches on it then compile
// away), or SHADOW_FILTER_ANY.
float lightVisibility(int kind, int index, vec3 lightVector, float size, vec3 position, vec3 normal,
                      vec3 towardLight) {
    if (kind == SHADOW_FILTER_NONE || u_shadowFilter.w < 0.5 || index >= MAX_SHADOW_LIGHTS) return 1.0;
    ivec4 record = u_shadowLights[index];
    if (kind == SHADOW_FILTER_ANY)
        kind = record.x == SHADOW_CASCADES ? SHADOW_FILTER_CASCADES
               : record.x == SHADOW_CUBE || record.x == SHADOW_SPOT ? (size > 0.0 ? SHADOW_FILTER_PCSS : SHADOW_FILTER_PCF)
               : SHADOW_FILTER_NONE;
    float radius = u_shadowFilter.x;
    // First the view and the receiver's map coordinates (arithmetic only), then one filtered lookup.
    int view = -1;
    vec3 coord = vec3(0.0);   // uv, depth
    if (kind == SHADOW_FILTER_CASCADES) {
        // The first cascade whose square holds the point with the kind's reach to spare (the cascades are
        // ordered near to far and cached squares may be larger than needed).
        float guard = (radius + 2.0) * u_shadowMapSizes.x;
        for (int k = record.z - 1; k >= 0; --k) {
            int v = record.y + k;
            vec3 p = shadowReceiver(position, normal, towardLight, u_shadowViewInfo[v].x);
            vec3 clip = (u_shadowViews[v] * vec4(p, 1.0)).xyz;
            vec2 uv = clip.xy * 0.5 + 0.5;
            if (all(greaterThanEqual(uv, vec2(guard))) && all(lessThanEqual(uv, vec2(1.0 - guard)))) {
                view = v;
                coord = vec3(uv, clip.z);
            }
        }
        if (view < 0) return 1.0;   // beyond shadow.distance
        return shadowPcfSun(coord.xy, u_shadowViewInfo[view].y, coord.z, u_shadowMapSizes.x, radius);
    }
    if (kind == SHADOW_FILTER_PCF || kind == SHADOW_FILTER_PCSS) {
        // A cube: the face of the major axis (faces are a little wider than 90 degrees: the kind stays on the
        // face). A spot: its one view. Both are perspective views whose clip w is the view depth.
        vec3 d = position - lightVector;
        vec3 a = abs(d);
        int face = a.x >= a.y && a.x >= a.z ? (d.x > 0.0 ? 0 : 1) : (a.y >= a.z ? (d.y > 0.0 ? 2 : 3) : (d.z > 0.0 ? 4 : 5));
        view = record.y + (record.x == SHADOW_CUBE ? face : 0);
        float depth = max((u_shadowViews[view] * vec4(position, 1.0)).w, 1e-4);
        vec3 p = shadowReceiver(position, normal, towardLight, u_shadowViewInfo[view].x * depth);
        vec4 clip = u_shadowViews[view] * vec4(p, 1.0);
        vec3 ndc = clip.xyz / max(clip.w, 1e-4);   // behind a spot: finite, and outside the map below
        vec2 uv = ndc.xy * 0.5 + 0.5;
        float shadow = kind == SHADOW_FILTER_PCSS
                           ? shadowPcssLocal(uv, u_shadowViewInfo[view].y, ndc.z, clip.w, u_shadowViewInfo[view].x,
                                             size, radius)
                           : shadowPcfLocal(uv, u_shadowViewInfo[view].y, ndc.z, u_shadowMapSizes.y, radius);
        // Outside a spot's view (beyond its outer cone, where it sends no light) nothing is shadowed.
        bool inView = clip.w > 1e-4 && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
        return inView ? shadow : 1.0;
    }
    return 1.0;
}

// The G-buffer pixel that mask texel `texel` was computed at (shaders/shadows/shadow_mask.frag).
ivec2 shadowMaskPixel(ivec2 texel, ivec2 viewport) { return reducedSamplePixel(texel, u_shadowMask.x, viewport); }

// The visibility of every shadowed light at G-buffer `pixel` from the shadow mask, per layer (slot = 4 x layer +
// channel; layers beyond u_shadowMask.z are 1). A full-resolution mask is read at the pixel; a reduced one is
// interpolated with `taps` (common/plane_aware_upsample.glsl: planeAwareTaps at u_shadowMask.x, unused at 1).
void shadowMaskVisibility(ivec2 pixel, UpsampleTaps taps, out vec4 visibility[MAX_SHADOW_SLOTS / 4]) {
    if (u_shadowMask.x == 1) {   // a full-resolution mask: this pixel's own texel (the branch is uniform)
        for (int layer = 0; layer < MAX_SHADOW_SLOTS / 4; ++layer)
            visibility[layer] = layer < u_shadowMask.z ? texelFetch(s_shadowMask, ivec3(pixel, layer), 0) : vec4(1.0);
        return;
    }
    for (int layer = 0; layer < MAX_SHADOW_SLOTS / 4; ++layer) {
        visibility[layer] = vec4(1.0);
        if (layer >= u_shadowMask.z) continue;
        vec4 sum = vec4(0.0);
        for (int k = 0; k < 4; ++k) sum += taps.weight[k] * texelFetch(s_shadowMask, ivec3(taps.texel[k], layer), 0);
        visibility[layer] = sum / taps.total;
    }
}

// The shadow mask's last texel (for planeAwareTaps).
ivec2 shadowMaskLastTexel() { return textureSize(s_shadowMask, 0).xy - 1; }

// Light `index`'s visibility from shadowMaskVisibility's result: 1 for lights without a shadow map.
float maskedLightVisibility(int index, vec4 visibility[MAX_SHADOW_SLOTS / 4]) {
    int slot = index < MAX_SHADOW_LIGHTS ? u_shadowLights[index].w : -1;
    return slot < 0 ? 1.0 : visibility[slot >> 2][slot & 3];
}
