// The Kurt et al. 2010 BRDF as used by "Real-time Rendering of Glossy Materials with Regular Sampling" (CGI 2014),
// Sec. 4, shared by the IBL modes regular, fis and reference (CPU reference: engine/environment/ibl/kurt_brdf.cpp).
// Shading frame: x = t, y = b, z = n. Lobe records and patterns are built by engine/environment/ibl/kurt_ibl_resources.cpp.
#include "common/bindings.glsl"
#include "common/constants.glsl"

struct KurtLobeGpu {
    vec4 roughness;   // mx, my, ks, shadowing exponent alpha
    vec4 fresnel;     // rgb r0 (negative: the material's metalness-workflow F0)
    vec4 pattern;     // first half vector, count, pdf constant (Eq. 18), xi0
};
layout(std430, binding = BINDING_IBL_FIRST + 0) readonly buffer KurtMaterialBlock { ivec4 u_kurtMaterials[]; };
layout(std430, binding = BINDING_IBL_FIRST + 1) readonly buffer KurtLobeBlock { KurtLobeGpu u_kurtLobes[]; };
layout(std430, binding = BINDING_IBL_FIRST + 2) readonly buffer KurtPatternBlock { vec4 u_kurtHalfVectors[]; };

// With ibl.pyramid = box | gauss4 | gauss6: the environment re-filtered with that pyramid (Sec. 3), else the
// environment's own box chain (envRadiance). Both apply env.intensity and env.rotation.
// With ibl.object_maps = 1, pixels of a material with a per-object map (Sec. 3; world frame, rendered radiance)
// read that map instead; kurtSelectObjectMap picks it once per pixel.
layout(binding = UNIT_IBL_FIRST) uniform samplerCube u_kurtEnvironment;
layout(binding = UNIT_IBL_FIRST + 1) uniform samplerCube u_kurtObjectMap0;
layout(binding = UNIT_IBL_FIRST + 2) uniform samplerCube u_kurtObjectMap1;
layout(binding = UNIT_IBL_FIRST + 3) uniform samplerCube u_kurtObjectMap2;
layout(binding = UNIT_IBL_FIRST + 4) uniform samplerCube u_kurtObjectMap3;
layout(binding = UNIT_IBL_FIRST + 5) uniform samplerCube u_kurtObjectMap4;
layout(binding = UNIT_IBL_FIRST + 6) uniform samplerCube u_kurtObjectMap5;
layout(binding = UNIT_IBL_FIRST + 7) uniform samplerCube u_kurtObjectMap6;
layout(std430, binding = BINDING_IBL_FIRST + 3) readonly buffer KurtObjectMapBlock { int u_kurtObjectMapSlot[]; };
int g_kurtObjectMap = -1;

void kurtSelectObjectMap(int materialId) {
    g_kurtObjectMap = -1;
#ifdef IBL_OBJECT_MAPS
    if (IBL_OBJECT_MAPS > 0.5 && materialId >= 0 && materialId < u_kurtObjectMapSlot.length())
        g_kurtObjectMap = u_kurtObjectMapSlot[materialId];
#endif
}

vec3 kurtObjectMapLookup(vec3 d, float lod) {
    switch (g_kurtObjectMap) {   // one branch per unit: sampler arrays need dynamically uniform indices
        case 0: return textureLod(u_kurtObjectMap0, d, lod).rgb;
        case 1: return textureLod(u_kurtObjectMap1, d, lod).rgb;
        case 2: return textureLod(u_kurtObjectMap2, d, lod).rgb;
        case 3: return textureLod(u_kurtObjectMap3, d, lod).rgb;
        case 4: return textureLod(u_kurtObjectMap4, d, lod).rgb;
        case 5: return textureLod(u_kurtObjectMap5, d, lod).rgb;
        default: return textureLod(u_kurtObjectMap6, d, lod).rgb;
    }
}

// Face size of the map kurtEnvironment reads (N of Eq. 16).
float kurtEnvironmentFaceSize() {
    if (g_kurtObjectMap >= 0) return float(textureSize(u_kurtObjectMap0, 0).x);   // all object maps share a size
    return float(textureSize(u_envSource, 0).x);
}

// Direction in the frame of the map kurtEnvironment reads (object maps are world-aligned; for Eq. 16's cube term).
vec3 kurtMapDirection(vec3 worldDir) { return g_kurtObjectMap >= 0 ? worldDir : envDirection(worldDir); }

vec3 kurtEnvironment(vec3 worldDir, float lod) {
    if (g_kurtObjectMap >= 0) return kurtObjectMapLookup(worldDir, lod);
#ifdef IBL_PYRAMID
    if (IBL_PYRAMID > 0.5) return u_envParams.x * textureLod(u_kurtEnvironment, envDirection(worldDir), lod).rgb;
#endif
    return envRadiance(worldDir, lod);
}

// (first lobe, lobe count) of a material; out-of-range ids use material 0.
ivec2 kurtMaterialLobes(int materialId) {
    int id = (materialId >= 0 && materialId < u_kurtMaterials.length()) ? materialId : 0;
    return u_kurtMaterials[id].xy;
}

vec3 kurtR0(KurtLobeGpu lobe, vec3 materialF0) { return lobe.fresnel.x < 0.0 ? materialF0 : lobe.fresnel.rgb; }

// Eq. 5: q(h) = exp(-tan^2(theta_h) (cos^2(phi_h) / mx^2 + sin^2(phi_h) / my^2)).
float kurtQ(vec3 h, float mx, float my) {
    if (h.z <= 0.0) return 0.0;
    return exp(-(h.x * h.x / (mx * mx) + h.y * h.y / (my * my)) / (h.z * h.z));
}

// Eq. 4: D(h) = q(h) / (pi mx my cos^4(theta_h)).
float kurtD(vec3 h, float mx, float my) {
    if (h.z <= 0.0) return 0.0;
    float c2 = h.z * h.z;
    return kurtQ(h, mx, my) / (PI * mx * my * c2 * c2);
}

// Eq. 3 (per colour channel when r0 is a colour).
vec3 kurtFresnel(float u, vec3 r0) {
    float m = clamp(1.0 - u, 0.0, 1.0);
    float m2 = m * m;
    return r0 + (1.0 - r0) * (m2 * m2 * m);
}

// Eq. 2 without the lobe weight ks: F D / (4 (o.h) ((i.n)(o.n))^alpha).
vec3 kurtLobe(vec3 wi, vec3 wo, KurtLobeGpu lobe, vec3 r0) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return vec3(0.0);
    vec3 h = normalize(wi + wo);
    float oh = dot(wo, h);
    if (oh <= 0.0) return vec3(0.0);
    float d = kurtD(h, lobe.roughness.x, lobe.roughness.y);
    return kurtFresnel(oh, r0) * (d / (4.0 * oh * pow(wi.z * wo.z, lobe.roughness.w)));
}

// Eq. 6-7 (Eq. 6's arctan taken in the quadrant of 2 pi xi2), xi1 in (0, 1].
vec3 kurtSampleHalfVector(float xi1, float xi2, float mx, float my) {
    float a = 2.0 * PI * xi2;
    float phi = atan(my * sin(a), mx * cos(a));
    float c = cos(phi), s = sin(phi);
    float tan2 = -log(xi1) / (c * c / (mx * mx) + s * s / (my * my));
    float cosTheta = inversesqrt(1.0 + tan2);
    float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
    return vec3(sinTheta * c, sinTheta * s, cosTheta);
}

// Density of kurtSampleHalfVector over half-vector solid angle; Eq. 10 divides it by 4 (o.h).
float kurtHalfVectorPdf(vec3 h, float mx, float my) {
    if (h.z <= 0.0) return 0.0;
    return kurtQ(h, mx, my) / (PI * mx * my * h.z * h.z * h.z);
}

// Distance from the centre to the unit cube along the unit direction d (the cube-map distortion of Sec. 6).
float cubeDistance(vec3 d) {
    vec3 a = abs(d);
    return length(d) / max(a.x, max(a.y, a.z));
}

float radicalInverse2(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10;
}
