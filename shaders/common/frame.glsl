// Per-frame data shared by every pass. Mirrors FrameUniforms in engine/render/shader_interface.h (std140).
#include "common/bindings.glsl"
layout(std140, binding = BINDING_FRAME) uniform FrameBlock {
    mat4 u_view;
    mat4 u_projection;
    mat4 u_viewProjection;
    mat4 u_inverseViewProjection;
    vec4 u_cameraPosition;   // xyz
    vec4 u_skyColor;         // rgb: background and constant ambient radiance when no environment map is bound
    ivec4 u_viewport;        // width, height, frame index, debug view (AOV id)
    vec4 u_exposure;         // x: exposure multiplier (2^EV), y: light count, z: ambient scale, w: area lights (the
                             // last w of the y lights; the punctual ones come first)
    uvec4 u_sample;          // x: accumulation sample index (0 = first estimate of this view; IBL modes)
    vec4 u_jitter;           // xy: TAA sub-pixel jitter of this frame in pixels; z: 1 when glints are evaluated
                             // at the unjittered pixel centre (taa.stable_glints; docs/image.md); w: the glint
                             // footprint's scale (lighting.glint_footprint: render size / output size, else 1)
};

// Lights (std430). type: 0 directional (vector = unit direction towards the light), 1 point (vector = position),
// 2 spot (position; KHR_lights_punctual cone), 3 rect, 4 disk, 5 sphere (vector = centre; lights/area_light.glsl).
// GpuScene uploads the punctual lights (0-2) first, then the area lights (u_exposure.w of them).
struct GpuLight {
    vec4 vectorType;         // xyz vector, w type
    vec4 colorIntensity;     // rgb colour, a intensity (area lights: their radiance, intensity / area)
    vec4 spotAxisScale;      // spot: xyz unit direction the light shines along, w 1 / max(0.001, cos inner - cos outer)
    vec4 spotOffsetRange;    // x spot: -cos(outer) * scale; y range (0 = infinite); z size: directional: solid angle
                             // (sr), point and spot: radius (m), area lights: radius of a disk of their area (soft
                             // shadows); w intensity (area lights: as a point light of it seen from afar)
    vec4 areaU;              // rect: xyz half-extent along the width; disk: radius x width axis; w 1 when two-sided
    vec4 areaV;              // rect: half-extent along the height; disk: radius x height axis; sphere: w radius
};
layout(std430, binding = BINDING_LIGHTS) readonly buffer LightBlock { GpuLight u_lights[]; };

// World position of G-buffer `pixel` (its centre) at reversed-Z `depth`.
vec3 worldPosition(ivec2 pixel, float depth) {
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(u_viewport.xy) * 2.0 - 1.0;
    vec4 p = u_inverseViewProjection * vec4(ndc, depth, 1.0);
    return p.xyz / p.w;
}

// Materials (std430), indexed by the material id stored in the G-buffer.
struct GpuMaterial {
    vec4 baseColor;
    vec4 alphaMetallicNdfGlinty;      // x alpha, y metallic, z ndf (0 GGX, 1 Beckmann), w glinty (0/1)
    vec4 densityCutoff;               // x glint density scale, y alpha cutoff (< 0: opaque)
};
layout(std430, binding = BINDING_MATERIALS) readonly buffer MaterialBlock { GpuMaterial u_materials[]; };

// Debug views (--aov): VIEW_* ids, one list for the shaders and engine/render/aov.cpp.
#include "common/aov_ids.glsl"
