// IBL mode `ndf-is` (issue 5, the comparison of Kemppinen et al. 2025, Fig. 7): Monte Carlo integration of the
// environment with half vectors drawn from the SMOOTH NDF (density D(h) |h.n|, Walter et al. 2007), whatever the
// glint method; glinty materials still evaluate the method's NDF in f. One diffuse (cosine) and one specular sample
// per accumulation index. Unbiased for every method (the smooth NDF covers the whole hemisphere), but the glinty
// NDF's peaks are found only by chance, hence the noise glint-is removes.
#include "environment/ibl/microfacet_sampling.glsl"

vec3 iblRadiance(GlintPixel glint, GlintSurface s, vec3 wo, vec3 toEyeWorld, mat3 worldToShading, vec3 diffuseAlbedo,
                 vec3 f0, bool glinty, uint sampleIndex) {
    uint rng = iblSampleSeed(s.pixel, sampleIndex, uint(IBL_SEED));
    vec3 diffuse = iblDiffuseEstimate(s, diffuseAlbedo, rng);
    float u1 = iblRandom(rng), u2 = iblRandom(rng);
    vec3 h = iblSampleSmoothNdf(u1, u2, s.alpha, s.ndf);
    return diffuse + iblSpecularEstimate(glint, s, wo, worldToShading, f0, glinty, h, iblSmoothNdfPdf(h, s.alpha, s.ndf));
}
