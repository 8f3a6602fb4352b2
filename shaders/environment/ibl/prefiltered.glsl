// IBL mode `prefiltered` (default): the split-sum baseline of environment/prefiltered_lookup.glsl, one deterministic evaluation.
// Glinty materials get the smooth prefiltered lobe here; the glint methods act on the lights. Reflection probes
// (IblMode::readsProbes) replace the distant map where they cover the shaded point.
vec3 iblRadiance(GlintPixel glint, GlintSurface s, vec3 wo, vec3 toEyeWorld, mat3 worldToShading, vec3 diffuseAlbedo,
                 vec3 f0, bool glinty, uint sampleIndex) {
    return envLightingAt(s.position, s.n, toEyeWorld, diffuseAlbedo, f0, s.alpha, s.ndf);   // with local probes
}
