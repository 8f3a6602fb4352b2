// Environment glints (Kneiphof & Klein 2025, Sec. 4.1): the environment's luminance range above a black level by
// two reductions, then K log-spaced radiance levels (level 0 = 0, level 1 the darkest texel above the black level,
// level K - 1 the brightest). REDUCE_TEXELS: one workgroup per 16 x 16 texels of a face of the source cube's mip
// u_mip writes its (min, max); REDUCE_GROUPS: one workgroup reduces those and writes the levels
// (engine/environment/environment_glints.cpp).
#include "common/bindings.glsl"

layout(local_size_x = 16, local_size_y = 16, local_size_z = 1) in;

layout(std430, binding = BINDING_ENV_GLINTS) buffer EnvGlintBlock {
    vec4 levels[2];
    vec4 range;
    ivec4 info;
    vec2 partial[];   // per workgroup of the first pass: (min, max) luminance above the black level
};

layout(location = 0) uniform int u_size;        // face size of the mip read
layout(location = 1) uniform int u_mip;
layout(location = 2) uniform float u_blackLevel;
layout(location = 3) uniform int u_levels;      // K
layout(location = 4) uniform int u_groups;      // workgroups of the first pass

shared vec2 s_minMax[256];

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }   // Rec. 709

void reduceShared(uint i) {
    for (uint stride = 128u; stride > 0u; stride >>= 1u) {
        barrier();
        if (i < stride) s_minMax[i] = vec2(min(s_minMax[i].x, s_minMax[i + stride].x), max(s_minMax[i].y, s_minMax[i + stride].y));
    }
    barrier();
}

#ifdef REDUCE_TEXELS
layout(binding = UNIT_GLINT_LEVEL_SOURCE) uniform samplerCube u_source;
#include "environment/env_common.glsl"
void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    uint i = gl_LocalInvocationIndex;
    vec2 value = vec2(3.4e38, 0.0);
    if (id.x < u_size && id.y < u_size) {
        float y = luminance(textureLod(u_source, cubeDirection(id.z, vec2(id.xy) + 0.5, u_size), float(u_mip)).rgb);
        if (y > u_blackLevel && !isinf(y)) value = vec2(y, y);
    }
    s_minMax[i] = value;
    reduceShared(i);
    uvec3 groups = gl_NumWorkGroups;
    uint group = (gl_WorkGroupID.z * groups.y + gl_WorkGroupID.y) * groups.x + gl_WorkGroupID.x;
    if (i == 0u) partial[group] = s_minMax[0];
}
#endif

#ifdef REDUCE_GROUPS
void main() {
    uint i = gl_LocalInvocationIndex;
    vec2 value = vec2(3.4e38, 0.0);
    for (uint g = i; g < uint(u_groups); g += 256u) value = vec2(min(value.x, partial[g].x), max(value.y, partial[g].y));
    s_minMax[i] = value;
    reduceShared(i);
    if (i != 0u) return;
    vec2 extremes = s_minMax[0];
    bool any = extremes.y > u_blackLevel;
    float lo = any ? extremes.x : 0.0, hi = any ? extremes.y : 0.0;
    float l[8];
    l[0] = 0.0;
    for (int k = 1; k < 8; ++k) {
        // Log-spaced between lo and hi over levels 1 .. K - 1 (Sec. 4.1).
        float t = u_levels > 2 ? float(k - 1) / float(u_levels - 2) : 1.0;
        l[k] = k < u_levels && any ? lo * pow(hi / lo, t) : 0.0;
    }
    levels[0] = vec4(l[0], l[1], l[2], l[3]);
    levels[1] = vec4(l[4], l[5], l[6], l[7]);
    range = vec4(lo, hi, u_blackLevel, 0.0);
    info = ivec4(any ? u_levels : 0, u_levels > 4 ? 2 : 1, info.z, 0);
}
#endif
