// Compute shader for tests/kemppinen2025_ibl_test.cpp: runs the selected IBL mode's iblRadiance (the code the
// lighting pass runs) at one surface point given by uniforms, one invocation per accumulation sample index, and
// writes each estimate. The glint method and IBL mode files come in through the same include macros and
// parameter blocks as in lighting.frag; the environment is bound as for the lighting pass.
#include "common/frame.glsl"
#include "common/brdf.glsl"
#include "common/footprint.glsl"
#include "common/glint_surface.glsl"
#include "environment/prefiltered_lookup.glsl"
#include GLINT_METHOD_FILE
#include IBL_MODE_FILE

layout(local_size_x = 64) in;

layout(location = 0) uniform vec2 u_uv;
layout(location = 1) uniform vec4 u_duv;          // duv/dx, duv/dy
layout(location = 2) uniform float u_alpha;
layout(location = 3) uniform int u_ndf;
layout(location = 4) uniform uint u_sampleCount;
layout(location = 5) uniform ivec2 u_pixel;
layout(location = 6) uniform mat3 u_frame;        // columns: world tangent, bitangent, normal
layout(location = 9) uniform vec3 u_toEye;        // world
layout(location = 10) uniform vec3 u_f0;
layout(location = 11) uniform vec3 u_diffuseAlbedo;
layout(location = 12) uniform int u_glinty;

layout(std430, binding = 8) writeonly buffer EstimateBlock { vec4 o_estimates[]; };

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= u_sampleCount) return;
    GlintSurface s = makeGlintSurface(u_uv, u_duv.xy, u_duv.zw, u_alpha, u_ndf, 1.0, u_pixel, u_frame);
    mat3 worldToShading = transpose(u_frame);
    GlintPixel px = glintSetup(s);
    vec3 wo = worldToShading * u_toEye;
    vec3 radiance = iblRadiance(px, s, wo, u_toEye, worldToShading, u_diffuseAlbedo, u_f0, u_glinty != 0, index);
    o_estimates[index] = vec4(radiance, 0.0);
}
