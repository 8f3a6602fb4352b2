// IBL mode `reference`: Monte Carlo estimate of the Kurt BRDF (environment/ibl/kurt_brdf.glsl) under the environment, the
// reference of "Real-time Rendering of Glossy Materials with Regular Sampling" (CGI 2014, Sec. 8: > 10000 samples
// accumulated). Per frame IBL_SAMPLES importance samples per lobe (Eq. 6-7, pdf Eq. 10) and IBL_SAMPLES
// cosine-weighted samples of the diffuse term, all reading the unfiltered level 0; random numbers hashed from the
// pixel, the accumulation index and the sample index. The renderer averages frames (--spp).
#include "environment/ibl/kurt_brdf.glsl"

uint referenceHash(uint x) {   // lowbias32 integer hash
    x ^= x >> 16u; x *= 0x7feb352du;
    x ^= x >> 15u; x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

vec2 referenceRandom(ivec2 pixel, uint sampleIndex, uint i, uint stream) {
    uint seed = referenceHash(uint(pixel.x) * 0x9e3779b9u ^ referenceHash(uint(pixel.y) + 0x632be5abu));
    seed = referenceHash(seed ^ referenceHash(sampleIndex * 0x85ebca6bu + stream));
    uint a = referenceHash(seed + 2u * i), b = referenceHash(seed + 2u * i + 1u);
    return (vec2(a >> 8u, b >> 8u) + 0.5) / 16777216.0;   // in (0, 1)
}

vec3 iblRadiance(GlintPixel glint, GlintSurface s, vec3 wo, vec3 toEyeWorld, mat3 worldToShading, vec3 diffuseAlbedo,
                 vec3 f0, bool glinty, uint sampleIndex) {
    int n = int(IBL_SAMPLES);
    mat3 shadingToWorld = transpose(worldToShading);
    vec3 radiance = vec3(0.0);
    if (any(greaterThan(diffuseAlbedo, vec3(0.0)))) {   // kd/pi * int L cos: cosine-weighted, pdf cos/pi
        vec3 sum = vec3(0.0);
        for (int i = 0; i < n; ++i) {
            vec2 u = referenceRandom(s.pixel, sampleIndex, uint(i), 7u);
            float r = sqrt(u.x), phi = 2.0 * PI * u.y;
            vec3 wi = vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
            sum += envRadiance(shadingToWorld * wi, 0.0);
        }
        radiance += diffuseAlbedo * sum / float(n);
    }
    if (wo.z <= 0.0) return radiance;
    ivec2 lobes = kurtMaterialLobes(s.materialId);
    for (int l = 0; l < lobes.y; ++l) {
        KurtLobeGpu lobe = u_kurtLobes[lobes.x + l];
        vec3 r0 = kurtR0(lobe, f0);
        vec3 sum = vec3(0.0);
        for (int i = 0; i < n; ++i) {
            vec2 u = referenceRandom(s.pixel, sampleIndex, uint(i), uint(l));
            vec3 h = kurtSampleHalfVector(u.x, u.y, lobe.roughness.x, lobe.roughness.y);
            vec3 wi = 2.0 * dot(wo, h) * h - wo;
            float oh = dot(wo, h);
            if (wi.z <= 0.0 || oh <= 0.0) continue;
            float pdf = kurtHalfVectorPdf(h, lobe.roughness.x, lobe.roughness.y) / (4.0 * oh);
            sum += envRadiance(shadingToWorld * wi, 0.0) * kurtLobe(wi, wo, lobe, r0) * (wi.z / pdf);
        }
        radiance += lobe.roughness.z * sum / float(n);
    }
    return radiance;
}
