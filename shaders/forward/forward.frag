// Forward shading after the lighting pass (render/forward/emissive_pass.h, transparent_pass.h), with the G-buffer's
// vertex shader. FORWARD_EMISSIVE: the emitted radiance of opaque / masked materials, added. FORWARD_TRANSPARENT:
// a glTF BLEND surface (3.9.4) shaded like the lighting pass shades opaque ones (Cook-Torrance with the material's
// smooth NDF, Lambert, metalness; the prefiltered environment or the constant ambient; every light; emission) and
// its alpha, which the blend state composites "over" the radiance behind it. No glints on blended surfaces.
// KHR_materials_clearcoat in both: the coat is on top of the emission ("coated_emission = emission x (1 - c Fc)")
// and, on blended surfaces, of the whole base, with its own lobe added, as the lighting pass layers opaque ones
// (common/clearcoat.glsl). The coverage alpha covers the coated surface as a whole.
#include "common/bindings.glsl"
#include "common/frame.glsl"
#include "common/brdf.glsl"
#include "common/footprint.glsl"
#include "common/material_textures.glsl"
#include "environment/prefiltered_lookup.glsl"
#include "common/light_incidence.glsl"
#include "common/clearcoat.glsl"
#include "common/clearcoat_material.glsl"

in vec3 v_normal;
in vec4 v_tangent;
in vec2 v_uv;
in vec4 v_color;

layout(location = 2) uniform int u_materialIndex;
layout(location = 3) uniform int u_textureMask;     // bits: 0 base colour, 1 metal-rough, 2 normal, 3 occlusion, 5 emissive, 6-8 coat
layout(location = 4) uniform mat3 u_uvTransform;
layout(location = 5) uniform vec3 u_emissive;       // emissiveFactor x emissiveStrength (linear)

layout(binding = UNIT_MATERIAL_BASE_COLOR) uniform sampler2D t_baseColor;
layout(binding = UNIT_MATERIAL_METALLIC_ROUGHNESS) uniform sampler2D t_metallicRoughness;
layout(binding = UNIT_MATERIAL_NORMAL) uniform sampler2D t_normal;
layout(binding = UNIT_MATERIAL_OCCLUSION) uniform sampler2D t_occlusion;
layout(binding = UNIT_MATERIAL_EMISSIVE) uniform sampler2D t_emissive;
layout(binding = UNIT_FORWARD_CLEARCOAT) uniform sampler2D t_clearcoat;
layout(binding = UNIT_FORWARD_CLEARCOAT_ROUGHNESS) uniform sampler2D t_clearcoatRoughness;
layout(binding = UNIT_FORWARD_CLEARCOAT_NORMAL) uniform sampler2D t_clearcoatNormal;

layout(location = 0) out vec4 o_color;

vec3 finiteOrZero(vec3 c) {
    bvec3 bad = bvec3(isnan(c.x) || isinf(c.x), isnan(c.y) || isinf(c.y), isnan(c.z) || isinf(c.z));
    return any(bad) ? vec3(0.0) : c;
}

void main() {
    GpuMaterial material = u_materials[u_materialIndex];
    vec2 textureUv = (u_uvTransform * vec3(v_uv, 1.0)).xy;
    TextureFootprint footprint = textureFootprint(textureUv);
    vec4 baseColor = material.baseColor * v_color;
    if ((u_textureMask & 1) != 0) baseColor *= sampleTexture(t_baseColor, textureUv, footprint);
    // glTF 3.9.2: emissive = emissiveFactor x emissiveTexture (sRGB, decoded by the texture format).
    vec3 emission = u_emissive;
    if ((u_textureMask & 32) != 0) emission *= sampleTexture(t_emissive, textureUv, footprint).rgb;

#ifdef FORWARD_EMISSIVE
    if (material.densityCutoff.y >= 0.0 && baseColor.a < material.densityCutoff.y) discard;   // MASK: as the G-buffer
#endif
    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;
    vec3 t = v_tangent.xyz - n * dot(n, v_tangent.xyz);
    t = dot(t, t) > 1e-12 ? normalize(t) : normalize(cross(abs(n.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0), n));
    float bitangentSign = v_tangent.w < 0.0 ? -1.0 : 1.0;
    // Position from the fragment's window depth (clip control zero-to-one: NDC z = depth).
    vec2 ndc = gl_FragCoord.xy / vec2(u_viewport.xy) * 2.0 - 1.0;
    vec4 p = u_inverseViewProjection * vec4(ndc, gl_FragCoord.z, 1.0);
    vec3 position = p.xyz / p.w;
    vec3 toEye = normalize(u_cameraPosition.xyz - position);
    ClearcoatMaterial coatMaterial = clearcoatMaterial(material, u_textureMask, t_clearcoat, t_clearcoatRoughness,
                                                       t_clearcoatNormal, textureUv, footprint, n, t, bitangentSign);
    Clearcoat coat = clearcoatAt(coatMaterial.n, coatMaterial.intensity, coatMaterial.roughness, toEye);

#ifdef FORWARD_EMISSIVE
    o_color = vec4(finiteOrZero(emission * (1.0 - coat.weight)), 0.0);
#else
    float alpha = material.alphaMetallicNdfGlinty.x;
    float metallic = material.alphaMetallicNdfGlinty.y;
    int ndf = int(material.alphaMetallicNdfGlinty.z + 0.5);
    if ((u_textureMask & 2) != 0) {
        vec4 mr = sampleTexture(t_metallicRoughness, textureUv, footprint);   // glTF: G roughness, B metalness
        alpha *= mr.g * mr.g;
        metallic *= mr.b;
    }
    alpha = max(alpha, 1e-4);
    float occlusion = (u_textureMask & 8) != 0 ? sampleTexture(t_occlusion, textureUv, footprint).r : 1.0;

    if ((u_textureMask & 4) != 0) {
        vec3 tn = sampleTexture(t_normal, textureUv, footprint).xyz * 2.0 - 1.0;
        vec3 b = bitangentSign * cross(n, t);
        n = normalize(tn.x * t + tn.y * b + tn.z * n);
        t = normalize(t - n * dot(n, t));
    }
    vec3 b = bitangentSign * cross(n, t);
    mat3 worldToShading = transpose(mat3(t, b, n));
    vec3 wo = worldToShading * toEye;
    vec3 albedo = baseColor.rgb * occlusion;   // as the G-buffer: occlusion darkens the base colour
    vec3 f0 = mix(vec3(0.04), albedo, metallic);
    vec3 diffuseAlbedo = (1.0 - metallic) * albedo;

    vec3 radiance = envEnabled() ? envLighting(n, toEye, diffuseAlbedo, f0, alpha, ndf)
                                 : u_skyColor.rgb * u_exposure.z * diffuseAlbedo;
    bool coated = coat.weight > 0.0;
    vec3 coatRadiance = vec3(0.0);
    if (coated) {
        // The coat's environment lobe as the lighting pass computes it (split sum at the coat's roughness, GGX
        // table with F0 = 1; the constant ambient without an environment), from the distant map like the base.
        vec3 coatEnvironment = u_skyColor.rgb * u_exposure.z;
        if (envEnabled()) {
            vec2 ab = envBrdf(clamp(coat.nDotV, 1e-4, 1.0), coat.alpha, NDF_GGX);
            coatEnvironment = envPrefiltered(reflect(-toEye, coat.n), coat.alpha, NDF_GGX) * (ab.x + ab.y);
        }
        coatRadiance += coat.weight * coatEnvironment;
    }
    int lightCount = int(u_exposure.y);
    for (int i = 0; i < lightCount; ++i) {
        vec3 towardLight, irradiance;
        lightIncidence(u_lights[i], position, towardLight, irradiance);
        vec3 wi = worldToShading * towardLight;
        bool coatLit = coated && dot(coat.n, towardLight) > 0.0 && coat.nDotV > 0.0;
        if (coatLit) coatRadiance += coat.weight * clearcoatLobeCosine(coat, towardLight, toEye) * irradiance;
        if (wi.z <= 0.0 || wo.z <= 0.0) continue;
        vec3 h = normalize(wi + wo);
        vec3 specular = cookTorranceSpecular(D_smooth(h, alpha, ndf), wi, wo, h, alpha, ndf, f0);
        radiance += (diffuseAlbedo * INV_PI + specular) * irradiance * wi.z;
    }
    radiance += emission;
    if (coated) radiance = radiance * (1.0 - coat.weight) + coatRadiance;
    float coverage = clamp(baseColor.a, 0.0, 1.0);
    o_color = vec4(finiteOrZero(radiance), isnan(coverage) ? 0.0 : coverage);
#endif
}
