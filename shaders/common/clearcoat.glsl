// KHR_materials_clearcoat layering (Khronos KHR_materials_clearcoat, "Clearcoat"; glTF 2.0 Appendix B, fresnel_coat
// with ior 1.5): coated = base * (1 - c Fc) + c Fc * coat lobe, where c is the clear coat intensity,
// Fc = Schlick Fresnel with F0 = 0.04 at |n_c . v| (n_c the coat normal) and the coat lobe is the microfacet
// specular D G / (4 |n_c.l| |n_c.v|) of a GGX coat with alpha = clearcoatRoughness^2, without its own Fresnel (it is
// in the weight). The weight depends on the view only, so it scales the whole base radiance (diffuse, specular,
// glints, environment) once. G is the engine's separable Smith G of the base lobe (common/brdf.glsl), where the
// glTF appendix writes the height-correlated form: the same choice as the base, so a coat equal to the base
// lobe shades like it. The CPU reference is engine/reference/clearcoat_reference.h; keep both in step.
#ifndef GLIMMER_CLEARCOAT_GLSL
#define GLIMMER_CLEARCOAT_GLSL
#include "common/brdf.glsl"
#include "common/octahedral.glsl"

const float kClearcoatF0 = 0.04;          // ((1 - 1.5) / (1 + 1.5))^2
const float kClearcoatMinAlpha = 1e-3;    // the loader's floor of the base alpha: a coat of roughness 0 stays finite

struct Clearcoat {
    float weight;    // c Fc: the coat's share, 0 on uncoated pixels
    float alpha;     // GGX alpha of the coat
    vec3 n;          // world coat normal
    float nDotV;
};

// The coat at a point seen along toEye: world coat normal n, intensity and perceptual roughness.
Clearcoat clearcoatAt(vec3 n, float intensity, float roughness, vec3 toEye) {
    Clearcoat c;
    c.n = n;
    c.nDotV = dot(c.n, toEye);
    float fresnel = F_Schlick(vec3(kClearcoatF0), abs(c.nDotV)).x;
    c.weight = intensity > 0.0 ? clamp(intensity, 0.0, 1.0) * fresnel : 0.0;
    c.alpha = max(roughness * roughness, kClearcoatMinAlpha);
    return c;
}

// From G-buffer target 5 (gbuffer.frag): octahedral coat normal, intensity, perceptual roughness.
Clearcoat clearcoatFromGBuffer(vec4 texel, vec3 toEye) {
    return clearcoatAt(octahedralDecode(texel.xy), texel.z, texel.w, toEye);
}

// The coat lobe (without Fresnel) times n_c.l for unit world vectors l (to the light) and v (to the eye).
float clearcoatLobeCosine(Clearcoat c, vec3 l, vec3 v) {
    float nDotL = dot(c.n, l);
    if (nDotL <= 0.0 || c.nDotV <= 0.0) return 0.0;
    float nDotH = dot(c.n, normalize(l + v));
    float D = D_GGX(vec3(0.0, 0.0, nDotH), c.alpha);
    float G = G1_GGX(vec3(0.0, 0.0, nDotL), c.alpha) * G1_GGX(vec3(0.0, 0.0, c.nDotV), c.alpha);
    return D * G / max(4.0 * c.nDotV, 1e-7);   // D G / (4 n.l n.v) * n.l
}

#endif
