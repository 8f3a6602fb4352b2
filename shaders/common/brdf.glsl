// Microfacet BRDF terms in the shading frame (z = normal). Cook & Torrance 1982 with
// GGX (Walter et al. 2007, Eq. 33) or Beckmann (Walter et al. 2007, Eq. 25) distributions, separable Smith
// masking-shadowing G = G1(wi) G1(wo) (Walter et al. Eq. 23, 27, 34), Schlick Fresnel.
// The CPU reference of these formulas is engine/reference/brdf_reference.h; keep both in step.
#include "common/constants.glsl"

float D_GGX(vec3 h, float alpha) {
    if (h.z <= 0.0) return 0.0;
    float a2 = alpha * alpha;
    float cos2 = h.z * h.z;
    float d = cos2 * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

float D_Beckmann(vec3 h, float alpha) {
    if (h.z <= 0.0) return 0.0;
    float cos2 = h.z * h.z;
    float tan2 = (1.0 - cos2) / cos2;
    float a2 = alpha * alpha;
    return exp(-tan2 / a2) / (PI * a2 * cos2 * cos2);
}

float G1_GGX(vec3 w, float alpha) {
    if (w.z <= 0.0) return 0.0;
    float cos2 = w.z * w.z;
    float tan2 = max(1.0 - cos2, 0.0) / cos2;
    return 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2));
}

// Beckmann G1 with Walter et al.'s rational approximation of the Smith integral (Eq. 27).
float G1_Beckmann(vec3 w, float alpha) {
    if (w.z <= 0.0) return 0.0;
    float tanTheta = sqrt(max(1.0 - w.z * w.z, 0.0)) / w.z;
    if (tanTheta <= 0.0) return 1.0;
    float a = 1.0 / (alpha * tanTheta);
    if (a >= 1.6) return 1.0;
    return (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a);
}

float D_smooth(vec3 h, float alpha, int ndf) { return ndf == NDF_BECKMANN ? D_Beckmann(h, alpha) : D_GGX(h, alpha); }
float G1_smooth(vec3 w, float alpha, int ndf) { return ndf == NDF_BECKMANN ? G1_Beckmann(w, alpha) : G1_GGX(w, alpha); }

vec3 F_Schlick(vec3 f0, float cosTheta) {
    float m = clamp(1.0 - cosTheta, 0.0, 1.0);
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

// Cook-Torrance specular with a given NDF value D (smooth or glinty): D G F / (4 |wi.n| |wo.n|).
vec3 cookTorranceSpecular(float D, vec3 wi, vec3 wo, vec3 h, float alpha, int ndf, vec3 f0) {
    float G = G1_smooth(wi, alpha, ndf) * G1_smooth(wo, alpha, ndf);
    vec3 F = F_Schlick(f0, max(dot(wi, h), 0.0));
    return D * G * F / max(4.0 * wi.z * wo.z, 1e-7);
}
