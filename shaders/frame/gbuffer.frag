// G-buffer: everything the lighting pass and the glint NDFs need. UV derivatives are taken here, in the
// geometry pass, where they are valid (a full-screen pass has no surface to differentiate).
// Layout (mirrors engine/render/frame/gbuffer.h):
//   0 RGBA32F  uv.xy, duv/dx.xy        1 RGBA32F  duv/dy.xy, material id, bitangent sign
//   2 RGBA16F  normal.xyz, alpha       3 RGBA16F  tangent.xyz, metallic
//   4 RGBA8    base colour.rgb, glint density mask
//   5 RGBA16F  clear coat normal (octahedral).xy, clear coat, clear coat roughness (KHR_materials_clearcoat;
//              zero on uncoated materials; the lighting pass reads it at UNIT_GBUFFER_CLEARCOAT)
//   6 RGBA16F  with GBUFFER_SLOPE_COVARIANCE only (glint methods that filter normal maps): the LEAN-filtered normal
//              map's slope covariance Sigma_xx, Sigma_yy, Sigma_xy (zero without a normal map); the normal is then
//              the LEAN mean slope's (Olano & Baker 2010; Chermain et al. 2021)
#include "common/bindings.glsl"
#include "common/frame.glsl"
#include "common/footprint.glsl"
#include "common/material_textures.glsl"
#include "common/octahedral.glsl"
#include "common/clearcoat_material.glsl"

in vec3 v_normal;
in vec4 v_tangent;
in vec2 v_uv;
in vec4 v_color;

layout(location = 2) uniform int u_materialIndex;
layout(location = 3) uniform int u_textureMask;     // bit 0 base colour, 1 metal-rough, 2 normal, 3 occlusion, 4 glint mask,
                                                    // 6 clear coat, 7 clear coat roughness, 8 clear coat normal
layout(location = 4) uniform mat3 u_uvTransform;    // KHR_texture_transform for texture lookups only

layout(binding = UNIT_MATERIAL_BASE_COLOR) uniform sampler2D t_baseColor;
layout(binding = UNIT_MATERIAL_METALLIC_ROUGHNESS) uniform sampler2D t_metallicRoughness;
layout(binding = UNIT_MATERIAL_NORMAL) uniform sampler2D t_normal;
layout(binding = UNIT_MATERIAL_OCCLUSION) uniform sampler2D t_occlusion;
layout(binding = UNIT_MATERIAL_GLINT_MASK) uniform sampler2D t_glintMask;
layout(binding = UNIT_MATERIAL_CLEARCOAT) uniform sampler2D t_clearcoat;                     // R
layout(binding = UNIT_MATERIAL_CLEARCOAT_ROUGHNESS) uniform sampler2D t_clearcoatRoughness;  // G
layout(binding = UNIT_MATERIAL_CLEARCOAT_NORMAL) uniform sampler2D t_clearcoatNormal;
#ifdef GBUFFER_SLOPE_COVARIANCE
layout(binding = UNIT_MATERIAL_LEAN_MOMENTS) uniform sampler2D t_leanMoments;   // E[m], E[m_x^2], E[m_y^2]
layout(binding = UNIT_MATERIAL_LEAN_CROSS) uniform sampler2D t_leanCross;       // E[m_x m_y]
layout(location = 6) out vec4 o_slopeCovariance;
#endif

layout(location = 0) out vec4 o_uvDuvdx;
layout(location = 1) out vec4 o_duvdyMaterial;
layout(location = 2) out vec4 o_normalAlpha;
layout(location = 3) out vec4 o_tangentMetallic;
layout(location = 4) out vec4 o_baseColorMask;
layout(location = 5) out vec4 o_clearcoat;

void main() {
    GpuMaterial material = u_materials[u_materialIndex];
    // Fine derivatives: the difference with the horizontal / vertical neighbour in the 2x2 quad.
    vec2 duvdx = dFdxFine(v_uv);
    vec2 duvdy = dFdyFine(v_uv);
    vec2 textureUv = (u_uvTransform * vec3(v_uv, 1.0)).xy;
    TextureFootprint footprint = textureFootprint(textureUv);

    vec4 baseColor = material.baseColor * v_color;   // glTF 3.9.2: COLOR_0 multiplies the base colour
    if ((u_textureMask & 1) != 0) baseColor *= sampleTexture(t_baseColor, textureUv, footprint);
    if (material.densityCutoff.y >= 0.0 && baseColor.a < material.densityCutoff.y) discard;
    float alpha = material.alphaMetallicNdfGlinty.x;
    float metallic = material.alphaMetallicNdfGlinty.y;
    if ((u_textureMask & 2) != 0) {
        vec4 mr = sampleTexture(t_metallicRoughness, textureUv, footprint);   // glTF: G roughness, B metalness
        alpha *= mr.g * mr.g;                                 // alpha = roughness^2
        metallic *= mr.b;
    }
    float glintMask = 1.0;
#ifdef GBUFFER_EXTRA_TEXTURES   // a material of the scene has one of these textures (render/frame/gbuffer_pass.h)
    if ((u_textureMask & 8) != 0) baseColor.rgb *= sampleTexture(t_occlusion, textureUv, footprint).r;
    if ((u_textureMask & 16) != 0) glintMask = sampleTexture(t_glintMask, textureUv, footprint).r;
#endif

    vec3 n = normalize(v_normal);
    if (!gl_FrontFacing) n = -n;   // two-sided surfaces shade their back faces with the flipped normal
    vec3 t = v_tangent.xyz - n * dot(n, v_tangent.xyz);
    t = dot(t, t) > 1e-12 ? normalize(t) : normalize(cross(abs(n.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0), n));
    float bitangentSign = v_tangent.w < 0.0 ? -1.0 : 1.0;
#ifdef GBUFFER_EXTRA_TEXTURES
    const int coatTextureMask = u_textureMask;
#else
    const int coatTextureMask = 0;   // no clear-coat textures in the scene: the coat's factors alone
#endif
    ClearcoatMaterial coat = clearcoatMaterial(material, coatTextureMask, t_clearcoat, t_clearcoatRoughness,
                                               t_clearcoatNormal, textureUv, footprint, n, t, bitangentSign);
    vec3 slopeCovariance = vec3(0.0);
#ifdef GBUFFER_SLOPE_COVARIANCE
    if ((u_textureMask & 4) != 0 && (u_textureMask & 512) != 0) {
        // LEAN mapping: the filtered first and second moments of the normal map's slopes over the pixel's
        // footprint (the same lookups as the normal map's); the covariance goes to the glint method, the mean
        // slope gives the normal.
        vec4 moments = sampleTexture(t_leanMoments, textureUv, footprint);
        float crossMoment = sampleTexture(t_leanCross, textureUv, footprint).r;
        vec2 meanSlope = moments.xy;
        slopeCovariance = vec3(max(moments.z - meanSlope.x * meanSlope.x, 0.0),
                               max(moments.w - meanSlope.y * meanSlope.y, 0.0), crossMoment - meanSlope.x * meanSlope.y);
        vec3 tn = normalize(vec3(-meanSlope, 1.0));
        vec3 b = bitangentSign * cross(n, t);
        n = normalize(tn.x * t + tn.y * b + tn.z * n);
        t = normalize(t - n * dot(n, t));
    } else
#endif
    if ((u_textureMask & 4) != 0) {
        vec3 tn = sampleTexture(t_normal, textureUv, footprint).xyz * 2.0 - 1.0;
        vec3 b = bitangentSign * cross(n, t);
        n = normalize(tn.x * t + tn.y * b + tn.z * n);
        t = normalize(t - n * dot(n, t));
    }

    o_uvDuvdx = vec4(v_uv, duvdx);
    o_duvdyMaterial = vec4(duvdy, float(u_materialIndex), bitangentSign);
    o_normalAlpha = vec4(n, max(alpha, 1e-4));
    o_tangentMetallic = vec4(t, metallic);
    o_baseColorMask = vec4(baseColor.rgb, glintMask);
    o_clearcoat = coat.intensity > 0.0 ? vec4(octahedralEncode(coat.n), coat.intensity, coat.roughness) : vec4(0.0);
#ifdef GBUFFER_SLOPE_COVARIANCE
    o_slopeCovariance = vec4(slopeCovariance, 0.0);
#endif
}
