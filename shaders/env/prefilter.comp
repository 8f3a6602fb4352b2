// Prefiltered specular radiance for one roughness level (split-sum, Karis 2013, Eq. 3 with n = v = r):
//   L(r) = sum L(l_k) (n.l_k) / sum (n.l_k),  h_k ~ D(h) (n.h),  l_k = reflect(-r, h_k)
// for the NDF of this layer (0 GGX, 1 Beckmann). Each sample reads the source mip whose texel solid angle
// matches the sample's solid angle 1 / (N pdf(l)) (filtered importance sampling, Krivanek & Colbert 2008,
// GPU Gems 3 Eq. 20-1, 20-2), so a few hundred samples give a smooth result. With v = n, pdf(l) = D(h) / 4.
// Deviation: lod bias +0.5 instead of the paper's +1. Worst relative error against CPU quadrature of the same
// integral (tests/environment_test.cpp, synthetic map) was 3.0% with bias 0 (sample-pattern noise), 2.6% with
// +0.5, 5.6% with +1 (blurs wider than the narrow lobes of levels 1-2).
// All four channels are filtered: a reflection probe's alpha is its coverage by geometry (sky texels 0), which the
// lighting pass blends with the distant environment (render/reflection_probes.h); the environment's alpha is 1.
#include "env/env_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform samplerCube u_source;                     // full mip chain
layout(rgba32f, binding = 0) uniform writeonly imageCubeArray u_target;  // one level, all layers
layout(location = 0) uniform int u_size;          // face size of the target level
layout(location = 1) uniform float u_alpha;
layout(location = 2) uniform int u_ndf;           // also the target layer
layout(location = 3) uniform int u_sampleCount;
layout(location = 4) uniform int u_sourceSize;    // face size of source level 0
layout(location = 5) uniform float u_maxSourceLod;
layout(location = 6) uniform int u_firstLayer;   // layer of face 0 of NDF 0 (probes: 12 per probe)

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= u_size || id.y >= u_size) return;
    vec3 n = cubeDirection(id.z, vec2(id.xy) + 0.5, u_size);
    mat3 frame = frameAround(n);
    float texelSolidAngle = 4.0 * PI / (6.0 * float(u_sourceSize * u_sourceSize));
    vec4 sum = vec4(0.0);
    float weight = 0.0;
    for (int i = 0; i < u_sampleCount; ++i) {
        vec3 hLocal = sampleHalfVector(hammersley(uint(i), uint(u_sampleCount)), u_alpha, u_ndf);
        vec3 h = frame * hLocal;
        vec3 l = 2.0 * dot(n, h) * h - n;
        float nDotL = dot(n, l);
        if (nDotL <= 0.0) continue;
        float pdf = D_smooth(hLocal, u_alpha, u_ndf) * 0.25;
        float sampleSolidAngle = 1.0 / (float(u_sampleCount) * max(pdf, 1e-8));
        float lod = clamp(0.5 * log2(sampleSolidAngle / texelSolidAngle) + 0.5, 0.0, u_maxSourceLod);
        sum += textureLod(u_source, l, lod) * nDotL;
        weight += nDotL;
    }
    vec4 radiance = weight > 0.0 ? sum / weight : vec4(0.0);
    imageStore(u_target, ivec3(id.xy, u_firstLayer + u_ndf * 6 + id.z), radiance);
}
