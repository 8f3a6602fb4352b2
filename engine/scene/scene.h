// CPU-side scene description: meshes, materials (with glint switches), lights, named cameras, environment.
// Built-in scenes are generated (builtin_scenes.cpp); glTF and scene files fill the same structures.
#pragma once
#include <glm/glm.hpp>
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
// the forward pass after lighting (render/passes/transparent_pass.h).
enum class AlphaMode : int { Opaque = 0, Mask = 1, Blend = 2 };

enum class NdfType : int { Ggx = 0, Beckmann = 1 };

struct Material {
    std::string name;
    glm::vec4 baseColor{0.8f, 0.8f, 0.8f, 1.0f};
    float alpha = 0.3f;        // NDF roughness alpha (glTF roughness r gives alpha = r^2)
    float metallic = 0.0f;
    NdfType ndf = NdfType::Ggx;
    bool glinty = false;       // the current glint method replaces D only on glinty materials
    float glintDensityScale = 1.0f;  // multiplies the method's microfacet density (per material)
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
    glm::mat3 uvTransform{1.0f};  // KHR_texture_transform, applied to UV0 for every texture of the material
};

enum class LightType : int { Directional = 0, Point = 1 };

struct Light {
    LightType type = LightType::Directional;
    glm::vec3 vector{0.0f, 1.0f, 0.0f};  // directional: unit direction towards the light; point: position
    glm::vec3 color{1.0f};
    float intensity = 1.0f;               // directional: irradiance at normal incidence; point: intensity (W/sr-ish)
};

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
