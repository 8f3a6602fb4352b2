// Equirectangular map -> cube face texels (level 0). One bilinear sample at each texel centre: the 1k maps have
// about one equirect texel per cube texel at face size 256, so no supersampling is needed; smaller faces are
// built from this level by the mip chain.
#include "environment/env_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform sampler2D u_equirect;          // u repeats, v clamps
layout(rgba32f, binding = 0) uniform writeonly imageCube u_cube;
layout(location = 0) uniform int u_size;

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= u_size || id.y >= u_size) return;
    vec3 d = cubeDirection(id.z, vec2(id.xy) + 0.5, u_size);
    vec3 radiance = textureLod(u_equirect, equirectUv(d), 0.0).rgb;
    imageStore(u_cube, id, vec4(max(radiance, vec3(0.0)), 1.0));
}
