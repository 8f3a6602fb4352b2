// IBL mode `prefiltered` (default): the split-sum baseline of environment/prefiltered_lookup.glsl, one
// deterministic evaluation.
// Reflection probes (IblMode::readsProbes) replace the distant map where they cover the shaded point.
// Environment glints (Kneiphof & Klein 2025; ibl.glint_levels): on glinty pixels of a method that defines
// GLINT_ENVIRONMENT (deliot2023), the split-sum specular is multiplied by the method's glint attenuation for the
// environment's radiance levels along the reflected lobe, from the sky and from the probes (the authors' demo reads
// the sky only). Other methods get the smooth prefiltered lobe here and their glints from the lights.
#include "lights/ltc.glsl"
#include "environment/glint_levels.glsl"
vec3 iblRadiance(GlintPixel glint, GlintSurface s, vec3 wo, vec3 toEyeWorld, mat3 worldToShading, vec3 diffuseAlbedo,
                 vec3 f0, bool glinty, uint sampleIndex) {
#ifdef GLINT_ENVIRONMENT
    if (glinty && u_envGlintInfo.x > 1) {
        // envLightingAt's terms, with the specular one kept apart.
        float nDotV = clamp(dot(s.n, toEyeWorld), 1e-4, 1.0);
        vec3 r = reflect(-toEyeWorld, s.n);
        vec2 ab = envBrdf(nDotV, s.alpha, s.ndf);
        vec3 specularAlbedo = f0 * ab.x + ab.y;
        vec3 specular = envPrefilteredAt(s.position, r, s.alpha, s.ndf) * specularAlbedo;
        vec3 diffuse = diffuseAlbedo * (1.0 - specularAlbedo) * envDiffuse(s.n);
        GlintEnvironment env = envGlintsAt(s.position, r, s.alpha, s.ndf);
        env.ndfIntegral = ltcNdfOnlyIntegral(s.alpha, nDotV, s.ndf);
        specular *= glintEnvironmentFactor(glint, s, env);
        g_environmentGlintPart = specular;
        return diffuse + specular;
    }
#endif
    return envLightingAt(s.position, s.n, toEyeWorld, diffuseAlbedo, f0, s.alpha, s.ndf);   // with local probes
}
