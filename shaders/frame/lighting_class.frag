// Shading class of each pixel for the lighting pass (render/frame/lighting_pass.h): depth 1 where the G-buffer
// holds a glinty material, 0 elsewhere (sky included). The lighting pass then draws its method variant where the
// class is 1 and its non-glinty variant (compiled with glinty = false) where it is 0, each with an early
// depth test GL_EQUAL: llvmpipe executes both sides of a branch, so a per-pixel `if (glinty)` alone made every
// pixel pay for the method's light loop; a fragment the depth test rejects is never shaded.
#include "common/bindings.glsl"
#include "common/frame.glsl"

layout(binding = UNIT_GBUFFER_DUVDY_MATERIAL) uniform sampler2D g_duvdyMaterial;
layout(binding = UNIT_GBUFFER_DEPTH) uniform sampler2D g_depth;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    bool drawn = texelFetch(g_depth, pixel, 0).r > 0.0;   // reversed-Z clear value 0: sky
    int materialId = int(texelFetch(g_duvdyMaterial, pixel, 0).z + 0.5);
    gl_FragDepth = drawn && u_materials[materialId].alphaMetallicNdfGlinty.w > 0.5 ? 1.0 : 0.0;
}
