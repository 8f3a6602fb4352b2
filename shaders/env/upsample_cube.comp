// Writes one level of the prefiltered cube-map array from a cube-map array of half its face size by seamless
// bilinear lookup (render/cube_prefilter.cpp: the two narrowest levels are computed at half resolution, where
// their lobes still span about two texels, and upsampled).
#include "env/env_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform samplerCubeArray u_half;
layout(rgba32f, binding = 0) uniform writeonly imageCubeArray u_target;
layout(location = 0) uniform int u_size;         // face size of the target level
layout(location = 1) uniform int u_ndf;          // layer set of the half-size array (0 or 1)
layout(location = 2) uniform int u_firstLayer;   // target layer of face 0 of NDF 0

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= u_size || id.y >= u_size) return;
    vec3 d = cubeDirection(id.z, vec2(id.xy) + 0.5, u_size);
    imageStore(u_target, ivec3(id.xy, u_firstLayer + u_ndf * 6 + id.z), textureLod(u_half, vec4(d, float(u_ndf)), 0.0));
}
