// KHR_materials_clearcoat from the material: factors x textures, and the coat's normal. The G-buffer pass stores
// the result in target 5 (read back by the lighting pass); the forward passes, whose surfaces have no G-buffer
// texel of their own (blended) or shade before it is read (emissive), call it directly. One function, so both
// read the coat the same way.
#ifndef GLIMMER_CLEARCOAT_MATERIAL_GLSL
#define GLIMMER_CLEARCOAT_MATERIAL_GLSL
#include "common/frame.glsl"
#include "common/material_textures.glsl"

struct ClearcoatMaterial {
    float intensity;   // clearcoatFactor x clearcoatTexture.r
    float roughness;   // perceptual: clearcoatRoughnessFactor x clearcoatRoughnessTexture.g
    vec3 n;            // world coat normal
};

// textureMask bits 6-8: coat, coat roughness and coat normal textures bound. n, t and bitangentSign are the
// geometric frame before the base's normal map: without its own normal texture the coat follows the geometric
// normal, not the base's normal map (a smooth varnish over a bumpy paint; KHR_materials_clearcoat
// "clearcoatNormalTexture").
ClearcoatMaterial clearcoatMaterial(GpuMaterial material, int textureMask, sampler2D coatTexture,
                                    sampler2D roughnessTexture, sampler2D normalTexture, vec2 uv,
                                    TextureFootprint footprint, vec3 n, vec3 t, float bitangentSign) {
    ClearcoatMaterial coat;
    coat.intensity = material.densityCutoff.z;
    coat.roughness = material.densityCutoff.w;
    if ((textureMask & 64) != 0) coat.intensity *= sampleTexture(coatTexture, uv, footprint).r;
    if ((textureMask & 128) != 0) coat.roughness *= sampleTexture(roughnessTexture, uv, footprint).g;
    coat.n = n;
    if ((textureMask & 256) != 0) {
        vec3 tn = sampleTexture(normalTexture, uv, footprint).xyz * 2.0 - 1.0;
        coat.n = normalize(tn.x * t + tn.y * (bitangentSign * cross(n, t)) + tn.z * n);
    }
    return coat;
}

#endif
