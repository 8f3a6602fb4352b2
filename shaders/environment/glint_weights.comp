// Environment glints (Kneiphof & Klein 2025, Sec. 4.1): each texel's luminance split between the two radiance levels
// that bracket it (linear weights, so that sum_i w_i L_i is the texel's luminance), written as indicator weights of
// levels 1..4 (slice 0) and 5..7 (slice 1) of a cube map that is then prefiltered like the radiance
// (engine/environment/environment_glints.cpp). Level 0 (radiance 0) is what the others leave: 1 - sum. Above the
// brightest level a texel is wholly the brightest (the probes may be brighter than the sky the levels came from).
// PROBE_SOURCE: the source is a reflection probe's cube (premultiplied radiance, coverage in alpha): the weights are
// premultiplied by the coverage, as the lighting pass blends them.
#include "common/bindings.glsl"
#include "environment/env_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(std430, binding = BINDING_ENV_GLINTS) readonly buffer EnvGlintBlock {
    vec4 levels[2];
    vec4 range;
    ivec4 info;
};
#ifdef PROBE_SOURCE
layout(binding = UNIT_GLINT_LEVEL_SOURCE) uniform samplerCubeArray u_source;
#else
layout(binding = UNIT_GLINT_LEVEL_SOURCE) uniform samplerCube u_source;
#endif
layout(rgba32f, binding = 0) uniform writeonly imageCube u_slice0;
layout(rgba32f, binding = 1) uniform writeonly imageCube u_slice1;
layout(location = 0) uniform int u_size;        // face size of the weights
layout(location = 1) uniform float u_sourceMip;
layout(location = 2) uniform int u_sourceCube;  // PROBE_SOURCE: the probe's layer (2 x probe)

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= u_size || id.y >= u_size) return;
    vec3 d = cubeDirection(id.z, vec2(id.xy) + 0.5, u_size);
#ifdef PROBE_SOURCE
    vec4 texel = textureLod(u_source, vec4(d, float(u_sourceCube)), u_sourceMip);
    float coverage = clamp(texel.a, 0.0, 1.0);
    float y = coverage > 1e-4 ? luminance(texel.rgb) / coverage : 0.0;
#else
    float coverage = 1.0;
    float y = luminance(textureLod(u_source, d, u_sourceMip).rgb);
#endif
    float w[8] = float[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    int count = info.x;
    if (count > 1 && y > 0.0 && !isinf(y)) {
        int top = count - 1;
        if (y >= levels[top >> 2][top & 3]) {
            w[top] = 1.0;
        } else {
            for (int k = 0; k < 7; ++k) {
                if (k + 1 > top) break;
                float lo = levels[k >> 2][k & 3], hi = levels[(k + 1) >> 2][(k + 1) & 3];
                if (y >= lo && y < hi) {
                    float t = hi > lo ? (y - lo) / (hi - lo) : 1.0;
                    w[k] = 1.0 - t;
                    w[k + 1] = t;
                }
            }
        }
    }
    imageStore(u_slice0, id, coverage * vec4(w[1], w[2], w[3], w[4]));
    imageStore(u_slice1, id, coverage * vec4(w[5], w[6], w[7], 0.0));
}
