// iblRadiance shared by the filtered Kurt-BRDF modes (regular.glsl, fis.glsl): SH diffuse (kd / pi x irradiance,
// Eq. 1's diffuse part) plus, for each Kurt lobe of the material, KURT_LOBE_RADIANCE(lobe, wo, shadingToWorld, r0),
// the mode's estimator of that lobe, which the including file defines before including this one. The material's
// own environment map is selected first (per-object maps, Sec. 3).
vec3 iblRadiance(GlintPixel glint, GlintSurface s, vec3 wo, vec3 toEyeWorld, mat3 worldToShading, vec3 diffuseAlbedo,
                 vec3 f0, bool glinty, uint sampleIndex) {
    vec3 radiance = diffuseAlbedo * envDiffuse(s.n);
    if (wo.z <= 0.0) return radiance;
    mat3 shadingToWorld = transpose(worldToShading);
    ivec2 lobes = kurtMaterialLobes(s.materialId);
    kurtSelectObjectMap(s.materialId);
    for (int l = 0; l < lobes.y; ++l) {
        KurtLobeGpu lobe = u_kurtLobes[lobes.x + l];
        radiance += KURT_LOBE_RADIANCE(lobe, wo, shadingToWorld, kurtR0(lobe, f0));
    }
    return radiance;
}
