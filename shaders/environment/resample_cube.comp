// Writes the six faces of one cube of a cube-map array into one mip of another by seamless bilinear lookup at each
// target texel's centre (environment/cube_prefilter.cpp): upsampling the levels computed at half resolution, and for a
// 2x downsampling exactly the box mean of the four texels under each target texel.
#include "environment/env_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform samplerCubeArray u_source;
layout(rgba32f, binding = 0) uniform writeonly imageCubeArray u_target;
layout(location = 0) uniform int u_size;              // face size of the target mip
layout(location = 1) uniform int u_sourceCube;        // cube of the source array
layout(location = 2) uniform int u_targetLayerFace;   // target layer-face of face 0
layout(location = 3) uniform int u_sourceMip;

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= u_size || id.y >= u_size) return;
    vec3 d = cubeDirection(id.z, vec2(id.xy) + 0.5, u_size);
    imageStore(u_target, ivec3(id.xy, u_targetLayerFace + id.z), textureLod(u_source, vec4(d, float(u_sourceCube)), float(u_sourceMip)));
}
