// CPU-side scene description: meshes, materials (with glint switches), lights, named cameras, environment.
// Built-in scenes are generated (builtin_scenes.cpp); glTF and scene files fill the same structures.
#pragma once
#include <glm/glm.hpp>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/camera.h"

namespace glimmer {

struct MeshData {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec4> tangents;  // xyz tangent (dP/du), w = handedness: bitangent = w * cross(n, t)
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> colors;    // glTF COLOR_0 (linear RGBA), multiplies the base colour; empty = white
    std::vector<uint32_t> indices;
    size_t triangleCount() const { return indices.size() / 3; }
};

// Texture sampler state (glTF 3.8.3 samplers): wrap modes per axis, and whether minification uses mipmaps.
enum class TextureWrap : int { Repeat = 0, ClampToEdge = 1, MirroredRepeat = 2 };
struct TextureSampler {
    TextureWrap wrapS = TextureWrap::Repeat, wrapT = TextureWrap::Repeat;
    bool mipmaps = true;        // false: glTF minFilter NEAREST or LINEAR (no mip levels are read)
    bool nearestMag = false;    // glTF magFilter NEAREST
    bool operator==(const TextureSampler&) const = default;
};

// 8-bit RGBA image for material textures (decoded on load; mipmaps are built on upload).
struct TextureData {
    std::string name;
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
    bool srgb = false;  // base colour textures are sRGB-encoded
    TextureSampler sampler;
};

// glTF alphaMode (3.9.4): OPAQUE ignores alpha, MASK cuts at alphaCutoff, BLEND is composited back to front in
// the forward pass after lighting (render/forward/transparent_pass.h).
enum class AlphaMode : int { Opaque = 0, Mask = 1, Blend = 2 };

enum class NdfType : int { Ggx = 0, Beckmann = 1 };

// One glint material in physical units, the same for every method (issue 17). Each method maps it to its own
// parameters (engine/glints/glint_mapping.h, README "Glint material"); the base NDF and roughness are the
// material's own (Material::ndf, Material::alpha). Defaults describe a medium-density metallic glitter.
struct GlintMaterial {
    float density = 2e6f;        // facets per square metre of surface (times the density mask texture)
    float angularSize = 0.015f;  // gamma: half-angle in radians of the cone around h in which one facet reflects
    glm::vec3 color{1.0f};       // linear tint of the glints (methods with per-glint colour)
    float colorVariation = 0.0f; // 0 = every glint has `color`, 1 = fully random hues around it
    float anisotropy = 1.0f;     // >= 1: glints stretched along the tangent by this factor
};

struct Material {
    std::string name;
    glm::vec4 baseColor{0.8f, 0.8f, 0.8f, 1.0f};
    float alpha = 0.3f;        // NDF roughness alpha (glTF roughness r gives alpha = r^2)
    float metallic = 0.0f;
    NdfType ndf = NdfType::Ggx;
    bool glinty = false;       // the current glint method replaces D only on glinty materials
    GlintMaterial glint;       // what the glints look like (used when glinty)
    float glintDensityScale = 1.0f;  // multiplies the glint density (kept for scene files written before `glint`)
    // Square metres of surface per unit UV area, so that densities per square metre become densities per UV area
    // (what the methods count in). 1 for the built-in scenes (UVs in metres); glTF models measure it per material.
    float surfacePerUvArea = 1.0f;
    float alphaCutoff = -1.0f; // >= 0: alpha mask
    bool blend = false;        // alphaMode BLEND: drawn by the transparent pass, not into the G-buffer
    // Emitted radiance (W sr^-1 m^-2 per unit, linear RGB): glTF emissiveFactor x KHR_materials_emissive_strength,
    // times emissiveTexture (sRGB) when present. Added by the emissive / transparent passes.
    glm::vec3 emissive{0.0f};
    int emissiveTexture = -1;
    // false: back faces are culled (glTF doubleSided: false). Only for surfaces whose back faces are never seen
    // (closed solids, walls against solids); two-sided ones shade back faces with the flipped normal.
    bool doubleSided = true;
    // Texture indices into Scene::textures, -1 when absent. Channel conventions follow glTF; the glint density
    // mask is read from the red channel of glintMaskTexture (spatially varying density).
    int baseColorTexture = -1;
    int metallicRoughnessTexture = -1;
    int normalTexture = -1;
    int occlusionTexture = -1;
    int glintMaskTexture = -1;
    // KHR_materials_clearcoat: a smooth dielectric layer (F0 0.04) over the whole material, glints included.
    // clearcoat = clearcoatFactor (x clearcoatTexture.r), clearcoatRoughness = clearcoatRoughnessFactor
    // (x clearcoatRoughnessTexture.g; perceptual, alpha = roughness^2). 0 = no coat (the material is unchanged).
    // Without clearcoatNormalTexture the coat follows the geometric normal, not the base's normal map.
    float clearcoat = 0.0f;
    float clearcoatRoughness = 0.0f;
    int clearcoatTexture = -1;
    int clearcoatRoughnessTexture = -1;
    int clearcoatNormalTexture = -1;  // its normalTextureInfo.scale is baked into the texture
    glm::mat3 uvTransform{1.0f};  // KHR_texture_transform, applied to UV0 for every texture of the material

    // The density scale the shaders see (GlintSurface::densityScale): zero when the glint material has no facets
    // (density 0), so every method renders no glints there, as where the density texture is 0. (Through the
    // methods' log-density parameters, ln 0 was clamped up to 0, one facet per unit UV area: sparse bright glints.)
    float shadingDensityScale() const { return glint.density > 0.0f ? glintDensityScale : 0.0f; }
};

// Every texture index of a material (for rebasing when models are merged into one scene: a slot left out here
// would keep indexing the first model's textures).
inline std::array<int*, 9> materialTextureSlots(Material& m) {
    return {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.normalTexture, &m.occlusionTexture, &m.glintMaskTexture,
            &m.emissiveTexture, &m.clearcoatTexture, &m.clearcoatRoughnessTexture, &m.clearcoatNormalTexture};
}

enum class LightType : int { Directional = 0, Point = 1, Spot = 2, Rect = 3, Disk = 4, Sphere = 5 };

// The sun's angular diameter (0.53 degrees), the default of every directional light.
constexpr float kSunAngularDiameter = 0.0092502f;

// Punctual lights (KHR_lights_punctual semantics) and area lights (rect, disk, sphere; shaded by linearly
// transformed cosines, engine/render/lights/). The lighting pass computes each punctual light's irradiance at normal
// incidence (intensity / d^2 x range window x cone falloff) and each area light's LTC integrals; a per-light
// visibility (shadows) multiplies either.
// Units (linear colour x intensity, per unit of the renderer's radiance): directional: irradiance at normal
// incidence (lux for photometric scenes); point, spot: intensity (candela); rect, disk: intensity along the normal
// (candela), so radiance = intensity / area and, seen from afar, the light equals a point light of that intensity
// times the cosine to its normal; sphere: intensity in every direction (candela), radiance = intensity / (pi r^2).
struct Light {
    LightType type = LightType::Directional;
    glm::vec3 vector{0.0f, 1.0f, 0.0f};  // directional: unit direction towards the light; others: position / centre
    glm::vec3 color{1.0f};
    float intensity = 1.0f;               // see the units above
    glm::vec3 spotDirection{0.0f, -1.0f, 0.0f};  // spot: unit direction it shines along; rect, disk: its normal (front)
    float innerConeAngle = 0.0f;          // spot: radians, full intensity inside
    float outerConeAngle = 0.7853982f;    // spot: radians, zero outside (KHR_lights_punctual defaults)
    float range = 0.0f;                   // point, spot, area: > 0 fades the light to zero at this distance; 0 = infinite
    // Size, which makes every light one of a solid angle (Kneiphof & Klein 2024: glints count the facets that see it):
    float angularDiameter = kSunAngularDiameter;   // directional: radians
    float radius = 0.0f;                  // point, spot: metres (0 = punctual); disk, sphere: metres
    glm::vec3 right{1.0f, 0.0f, 0.0f};    // rect, disk: unit axis of the width, orthogonal to spotDirection
    float width = 1.0f, height = 1.0f;    // rect: metres along right and along cross(spotDirection, right)
    bool twoSided = false;                // rect, disk: emits from both faces
    bool isArea() const { return type == LightType::Rect || type == LightType::Disk || type == LightType::Sphere; }
    // Emitting area in square metres (area lights), and the resulting radiance scale (intensity / area for rect and
    // disk, intensity / (pi r^2) for spheres).
    float area() const;
    float radianceScale() const;
};

// The order in which lights reach the GPU (render/gpu_scene.cpp, render/shadow_maps.cpp): the punctual lights in
// scene order, then the area lights in scene order (the lighting pass loops over each kind separately).
std::vector<size_t> gpuLightOrder(const std::vector<Light>& lights);

// KHR_lights_punctual's spot falloff: t = clamp((cos(angle to the axis) - cos outer) / (cos inner - cos outer)),
// attenuation t^2 (the extension's recommended smooth falloff). Shared with lighting.frag (tests compare them).
float spotAttenuation(float cosAngle, float innerConeAngle, float outerConeAngle);
// The extension's recommended range window: clamp(1 - (d / range)^4, 0, 1)^2 (1 when range = 0).
float rangeWindow(float distance, float range);

struct Instance {
    uint32_t mesh = 0;
    uint32_t material = 0;
    glm::mat4 transform{1.0f};
};

struct Scene {
    std::string name;
    std::vector<MeshData> meshes;
    std::vector<Material> materials;
    std::vector<TextureData> textures;
    std::vector<Instance> instances;
    std::vector<Light> lights;
    std::vector<Camera> cameras;   // first is the default
    std::vector<std::string> walkthrough;  // camera names in the order of a walkthrough path (may be empty)
    bool fallbackLights = false;   // the lights are a default sun / key + fill, not the model's or the file's own
    std::string environment;       // "" = the procedural default sky, "none", or an image path
    glm::vec3 skyColor{0.0f};      // background and constant ambient radiance when no environment is active
    std::vector<std::string> methodFiles;  // user glint methods of a scene file ("methodFiles"), resolved paths

    size_t triangleCount() const;
    const Camera& camera(const std::string& name) const;  // throws UsageError naming --camera
};

// Which way the bitangent (w * cross(n, t)) of generated tangent frames points in UV space.
//  - UvUp: along +dP/dv. The built-in scenes' metric UV frames (MeshBuilder), whose v runs up walls and along
//    the surface: (dP/du, dP/dv, n) is their right-handed frame, and the glint methods read slopes in it.
//  - ImageUp: along -dP/dv, the image's up. glTF's v runs down the image (3.7.2.1: origin top left) and its
//    normal maps are +Y up (3.9.3), so glTF models (and authored TANGENTs, whose w follows MikkTSpace) use this.
enum class BitangentConvention { UvUp, ImageUp };

// Fills normals' tangents when a mesh has none, from UV gradients per triangle (Lengyel's method); the
// handedness w follows `convention`.
void generateTangents(MeshData& mesh, BitangentConvention convention);

}  // namespace glimmer
