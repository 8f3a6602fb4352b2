// Shadow maps: depth only; alpha-masked materials (glTF MASK) drop the texels the G-buffer drops, so foliage and
// grilles cast the shadow of what is drawn. Without ALPHA_MASK (every other material) the stage does nothing and has
// no discard, so the depth test runs before it (render/shadows/shadow_map_pass.h).
#include "common/bindings.glsl"
#ifdef ALPHA_MASK
#include "common/frame.glsl"
#include "common/footprint.glsl"
#include "common/material_textures.glsl"

in vec2 v_uv;

layout(location = 2) uniform int u_materialIndex;
layout(location = 3) uniform int u_textureMask;     // bit 0: base colour texture bound
layout(location = 4) uniform mat3 u_uvTransform;

layout(binding = UNIT_MATERIAL_BASE_COLOR) uniform sampler2D t_baseColor;

void main() {
    float cutoff = u_materials[u_materialIndex].densityCutoff.y;
    if (cutoff >= 0.0) {
        float alpha = u_materials[u_materialIndex].baseColor.a;
        if ((u_textureMask & 1) != 0) {
            // An explicit isotropic level (the larger axis): a mask needs no sharper level. llvmpipe's filter
            // scans the quad's coordinate differences even at an explicit level, and even where this branch is
            // masked off (material_textures.glsl), so a footprint wider than the texture reads its 1x1 level at a
            // constant coordinate, which that scan cannot stretch over a huge uvScale.
            vec2 uv = (u_uvTransform * vec3(v_uv, 1.0)).xy;
            TextureFootprint footprint = textureFootprint(uv);
            bool wide = !(footprint.major <= 1.0);
            vec2 texels = uv * vec2(textureSize(t_baseColor, 0));
            float lod = 0.5 * log2(max(max(dot(dFdx(texels), dFdx(texels)), dot(dFdy(texels), dFdy(texels))), 1.0));
            alpha *= textureLod(t_baseColor, wide ? vec2(0.5) : uv, wide ? 64.0 : min(lod, 20.0)).a;
        }
        if (alpha < cutoff) discard;
    }
}
#else
void main() {}
#endif
