// Shared by the Monte Carlo IBL modes ndf_is.glsl and glint_is.glsl (issue 5): per-pixel random streams, sampling
// of the smooth NDF and of the cosine lobe, and the one-sample estimator of the reflected environment radiance
//   L_o(wo) = int L(wi) [ diffuseAlbedo / pi + D G F / (4 |wi.n| |wo.n|) ] |wi.n| dwi,
// the same Lambert + Cook-Torrance model as the light loop of lighting.frag (D = the glint method's NDF on glinty
// materials, the smooth NDF otherwise). Deviation from the `prefiltered` mode: the diffuse term is not weighted by
// (1 - specular albedo), so a Monte Carlo mode and a light agree on what the surface reflects.
// CPU twin: engine/reference/ibl_sampling_reference.{h,cpp}.

// PCG-RXS-M-XS 32 (O'Neill 2014) step: uniform floats in [0, 1) with 24 bits.
float iblRandom(inout uint state) {
    state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    word = (word >> 22u) ^ word;
    return float(word >> 8u) * (1.0 / 16777216.0);
}

// A 32-bit integer finaliser (the PCG output permutation applied to an LCG step); chained to combine keys.
uint iblHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The random stream of one pixel and one accumulation sample: pixels and sample indices are decorrelated by
// hashing both (and the mode's `seed` parameter, which makes independent renders for references).
uint iblSampleSeed(ivec2 pixel, uint sampleIndex, uint seed) {
    return iblHash(uint(pixel.x) ^ iblHash(uint(pixel.y) ^ iblHash(sampleIndex ^ iblHash(seed))));
}

// Half vector with density D(h) |h.n| over solid angle (Walter et al. 2007, Eq. 28-29 Beckmann, Eq. 35-36 GGX).
vec3 iblSampleSmoothNdf(float u1, float u2, float alpha, int ndf) {
    float a2 = alpha * alpha;
    float tan2 = ndf == NDF_BECKMANN ? -a2 * log(max(1.0 - u1, 1e-12)) : a2 * u1 / max(1.0 - u1, 1e-12);
    float cosTheta = inversesqrt(1.0 + tan2);
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    float phi = 2.0 * PI * u2;
    return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

float iblSmoothNdfPdf(vec3 h, float alpha, int ndf) { return D_smooth(h, alpha, ndf) * max(h.z, 0.0); }

// Cosine-weighted direction (Malley's method: uniform disk lifted to the hemisphere), density cos / pi.
vec3 iblSampleCosine(float u1, float u2) {
    float r = sqrt(u1), phi = 2.0 * PI * u2;
    vec2 d = r * vec2(cos(phi), sin(phi));
    return vec3(d, sqrt(max(1.0 - u1, 0.0)));
}

// The NDF that multiplies the specular term in the light loop: the glint method's (RGB when it defines
// GLINT_COLOR_D) on glinty materials, the smooth NDF otherwise.
vec3 iblNdf(GlintPixel glint, GlintSurface s, vec3 h, vec3 wi, vec3 wo, bool glinty) {
    if (!glinty) return vec3(D_smooth(h, s.alpha, s.ndf));
#ifdef GLINT_COLOR_D
    return glintColorD(glint, s, h, wi, wo);
#else
    return vec3(glintD(glint, s, h, wi, wo));
#endif
}

// One specular estimate f cos / pdf x L for a half vector h drawn with solid-angle density pdfH:
// wi = reflect(-wo, h), pdf(wi) = pdfH / (4 |wo.h|), so f cos / pdf = D G F |wo.h| / (|wo.n| pdfH).
vec3 iblSpecularEstimate(GlintPixel glint, GlintSurface s, vec3 wo, mat3 worldToShading, vec3 f0, bool glinty,
                         vec3 h, float pdfH) {
    float woDotH = dot(wo, h);
    if (pdfH <= 0.0 || h.z <= 0.0 || woDotH <= 0.0 || wo.z <= 0.0) return vec3(0.0);
    vec3 wi = 2.0 * woDotH * h - wo;
    if (wi.z <= 0.0) return vec3(0.0);
    vec3 D = iblNdf(glint, s, h, wi, wo, glinty);
    float G = G1_smooth(wi, s.alpha, s.ndf) * G1_smooth(wo, s.alpha, s.ndf);
    vec3 F = F_Schlick(f0, woDotH);
    vec3 weight = D * G * F * (woDotH / (wo.z * pdfH));
    // worldToShading is orthonormal: its transpose takes the direction back to world space. The reflection probe
    // at the shaded point (if any) replaces the distant map where it saw geometry.
    return weight * envRadianceAt(s.position, transpose(worldToShading) * wi);
}

// One diffuse estimate: cosine-weighted sampling makes (albedo / pi) cos / pdf = albedo.
vec3 iblDiffuseEstimate(GlintSurface s, vec3 diffuseAlbedo, inout uint rng) {
    float u1 = iblRandom(rng), u2 = iblRandom(rng);
    if (all(equal(diffuseAlbedo, vec3(0.0)))) return vec3(0.0);
    vec3 l = iblSampleCosine(u1, u2);
    return diffuseAlbedo * envRadiance(l.x * s.t + l.y * s.b + l.z * s.n, 0.0);
}
