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
    std::vector<uint32_t> indices;
    size_t triangleCount() const { return indices.size() / 3; }
};

// 8-bit RGBA image for material textures (decoded on load; mipmaps are built on upload).
struct TextureData {
    std::string name;
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
    bool srgb = false;  // base colour textures are sRGB-encoded
};

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

// Fills normals' tangents when a mesh has none, from UV gradients per triangle (Lengyel's method).
void generateTangents(MeshData& mesh);

}  // namespace glimmer
