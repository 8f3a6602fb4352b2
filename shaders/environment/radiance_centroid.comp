// Level 0 of the prefilter's two sum chains (shaders/environment/prefilter.comp), per source texel of solid angle dw:
//   u_weighted = L dw (all four channels),  u_centroid = (luminance x dw x direction, dw).
// Their box mips are then 4^-m times the sums over the texels a mip-m texel covers, so the walk reads each coarse
// texel's exact integral of L and exact solid angle (the source's own box mips weight a face corner's small texels
// like its centre's, which over a 4 x 4 face misweights a lamp by up to 5x), and where its light comes from.
#include "environment/env_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform sampler2DArray u_radiance;          // source cube faces as layers
layout(rgba32f, binding = 0) uniform writeonly image2DArray u_weighted;
layout(rgba32f, binding = 1) uniform writeonly image2DArray u_centroid;
layout(location = 0) uniform int u_size;                         // face size of source level 0

// Solid angle of the face region [-1, s] x [-1, t] seen from the cube's centre, up to a constant
// (the area of a gnomonic rectangle: atan(s t / sqrt(s^2 + t^2 + 1))).
float cornerArea(float s, float t) { return atan(s * t, sqrt(s * s + t * t + 1.0)); }

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= u_size || id.y >= u_size) return;
    vec2 lo = 2.0 * vec2(id.xy) / float(u_size) - 1.0, hi = 2.0 * vec2(id.xy + 1) / float(u_size) - 1.0;
    float solidAngle = cornerArea(hi.x, hi.y) - cornerArea(lo.x, hi.y) - cornerArea(hi.x, lo.y) + cornerArea(lo.x, lo.y);
    vec4 radiance = max(texelFetch(u_radiance, id, 0), vec4(0.0));
    float luminance = dot(radiance.rgb, vec3(0.2126, 0.7152, 0.0722));
    vec3 direction = cubeDirection(id.z, vec2(id.xy) + 0.5, u_size);
    imageStore(u_weighted, id, radiance * solidAngle);
    imageStore(u_centroid, id, vec4(direction * (luminance * solidAngle), solidAngle));
}
