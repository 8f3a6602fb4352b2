// IBL mode `glint-is` (issue 5): image-based lighting with half vectors importance-sampled from the FILTERED GLINTY
// NDF of Kemppinen et al. 2025 (Sec. 3.3.5, Algorithm 2, shaders/glints/kemppinen2025/kemppinen2025_sampling.glsl), with the
// pdf it returns, in the estimator f cos / pdf x L of the paper's environment-lighting results (Fig. 7). Requires
// --method kemppinen2025 (the table entry says so; the renderer refuses other methods with a one-line error).
// Non-glinty materials sample the smooth NDF as ndf-is does. One diffuse (cosine) and one specular sample per
// accumulation index.
#include "glints/kemppinen2025/kemppinen2025_sampling.glsl"
#include "environment/ibl/microfacet_sampling.glsl"

vec3 iblRadiance(GlintPixel glint, GlintSurface s, vec3 wo, vec3 toEyeWorld, mat3 worldToShading, vec3 diffuseAlbedo,
                 vec3 f0, bool glinty, uint sampleIndex) {
    uint rng = iblSampleSeed(s.pixel, sampleIndex, uint(IBL_SEED));
    vec3 diffuse = iblDiffuseEstimate(s, diffuseAlbedo, rng);
    vec3 h;
    float pdfH;
    if (glinty) {
        vec2 prior;
        uint glintRng = iblHash(rng);   // the sampler's own stream (kemppinenRandom has the same PCG step)
        h = kemppinenSampleHalfVector(glint, s.ndf, glintRng, pdfH, prior);
    } else {
        float u1 = iblRandom(rng), u2 = iblRandom(rng);
        h = iblSampleSmoothNdf(u1, u2, s.alpha, s.ndf);
        pdfH = iblSmoothNdfPdf(h, s.alpha, s.ndf);
    }
    return diffuse + iblSpecularEstimate(glint, s, wo, worldToShading, f0, glinty, h, pdfH);
}
