// Split-sum BRDF table (Karis 2013, Eq. 4): the specular lobe's directional albedo written f0 * A + B, with
//   A = E[(1 - Fc) G (v.h) / ((n.h)(n.v))],  B = E[Fc G (v.h) / ((n.h)(n.v))],  Fc = (1 - v.h)^5,
// expectations over half vectors h ~ D(h)(n.h) (the D, G and Schlick F of common/brdf.glsl).
// Texel (x, y) holds n.v = (x + 0.5) / size and sqrt(alpha) = (y + 0.5) / size; rg GGX, ba Beckmann.
#include "environment/env_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba32f, binding = 0) uniform writeonly image2D u_lut;
layout(location = 0) uniform int u_size;
layout(location = 1) uniform int u_sampleCount;

vec2 integrate(float nDotV, float alpha, int ndf) {
    vec3 v = vec3(sqrt(max(1.0 - nDotV * nDotV, 0.0)), 0.0, nDotV);
    vec2 ab = vec2(0.0);
    for (int i = 0; i < u_sampleCount; ++i) {
        vec3 h = sampleHalfVector(hammersley(uint(i), uint(u_sampleCount)), alpha, ndf);
        float vDotH = dot(v, h);
        vec3 l = 2.0 * vDotH * h - v;
        if (l.z <= 0.0 || vDotH <= 0.0) continue;
        float g = G1_smooth(l, alpha, ndf) * G1_smooth(v, alpha, ndf);
        float weight = g * vDotH / (h.z * nDotV);
        float fc = pow(1.0 - vDotH, 5.0);
        ab += vec2((1.0 - fc) * weight, fc * weight);
    }
    return ab / float(u_sampleCount);
}

void main() {
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    if (id.x >= u_size || id.y >= u_size) return;
    float nDotV = (float(id.x) + 0.5) / float(u_size);
    float r = (float(id.y) + 0.5) / float(u_size);
    float alpha = max(r * r, 1e-4);
    imageStore(u_lut, id, vec4(integrate(nDotV, alpha, NDF_GGX), integrate(nDotV, alpha, NDF_BECKMANN)));
}
