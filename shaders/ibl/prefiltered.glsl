// IBL mode `prefiltered` (default): the split-sum baseline of common/ibl.glsl for every material.
vec3 iblRadiance(GlintPixel glint, GlintSurface s, vec3 wo, vec3 toEyeWorld, mat3 worldToShading,
                 vec3 diffuseAlbedo, vec3 f0, bool glinty, uint sampleIndex) {
    return envLighting(s.n, toEyeWorld, diffuseAlbedo, f0, s.alpha, s.ndf);
}
