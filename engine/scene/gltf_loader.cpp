#include "scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cstring>
#include <functional>

#include "core/error.h"
#include "core/log.h"

namespace glimmer {
namespace {

std::string firstLine(const std::string& text) {
    size_t end = text.find('\n');
    return end == std::string::npos ? text : text.substr(0, end);
}

// Reads accessor elements as floats (normalized integer types are mapped to [0,1] / [-1,1]).
template <int N>
std::vector<glm::vec<N, float>> readFloatAccessor(const tinygltf::Model& model, int index, const std::string& file) {
    const tinygltf::Accessor& accessor = model.accessors.at(index);
    if (accessor.bufferView < 0) return std::vector<glm::vec<N, float>>(accessor.count, glm::vec<N, float>(0.0f));
    const tinygltf::BufferView& view = model.bufferViews.at(accessor.bufferView);
    const tinygltf::Buffer& buffer = model.buffers.at(view.buffer);
    int components = tinygltf::GetNumComponentsInType(accessor.type);
    int componentSize = tinygltf::GetComponentSizeInBytes(accessor.componentType);
    if (components < N || componentSize <= 0) throw Error(file + ": accessor " + std::to_string(index) + " has the wrong type");
    size_t stride = view.byteStride ? view.byteStride : size_t(components * componentSize);
    size_t offset = view.byteOffset + accessor.byteOffset;
    if (offset + stride * (accessor.count ? accessor.count - 1 : 0) + size_t(components * componentSize) > buffer.data.size())
        throw Error(file + ": accessor " + std::to_string(index) + " reads past its buffer");
    std::vector<glm::vec<N, float>> out(accessor.count);
    for (size_t i = 0; i < accessor.count; ++i) {
        const unsigned char* p = buffer.data.data() + offset + i * stride;
        for (int c = 0; c < N; ++c) {
            float v = 0.0f;
            switch (accessor.componentType) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&v, p + c * 4, 4); break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: v = p[c] / 255.0f; break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t s; std::memcpy(&s, p + c * 2, 2); v = s / 65535.0f; break; }
                case TINYGLTF_COMPONENT_TYPE_BYTE: v = std::max(int8_t(p[c]) / 127.0f, -1.0f); break;
                case TINYGLTF_COMPONENT_TYPE_SHORT: { int16_t s; std::memcpy(&s, p + c * 2, 2); v = std::max(s / 32767.0f, -1.0f); break; }
                default: throw Error(file + ": unsupported component type in accessor " + std::to_string(index));
            }
            out[i][c] = v;
        }
    }
    return out;
}

std::vector<uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& file) {
    const tinygltf::Accessor& accessor = model.accessors.at(index);
    const tinygltf::BufferView& view = model.bufferViews.at(accessor.bufferView);
    const tinygltf::Buffer& buffer = model.buffers.at(view.buffer);
    int size = tinygltf::GetComponentSizeInBytes(accessor.componentType);
    size_t stride = view.byteStride ? view.byteStride : size_t(size);
    size_t offset = view.byteOffset + accessor.byteOffset;
    if (size <= 0 || offset + stride * (accessor.count ? accessor.count - 1 : 0) + size > buffer.data.size())
        throw Error(file + ": index accessor " + std::to_string(index) + " reads past its buffer");
    std::vector<uint32_t> out(accessor.count);
    for (size_t i = 0; i < accessor.count; ++i) {
        const unsigned char* p = buffer.data.data() + offset + i * stride;
        if (size == 1) out[i] = p[0];
        else if (size == 2) { uint16_t s; std::memcpy(&s, p, 2); out[i] = s; }
        else std::memcpy(&out[i], p, 4);
    }
    return out;
}

glm::mat4 nodeMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::mat4 m;
        for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(node.matrix[i]);
        return m;
    }
    glm::mat4 m(1.0f);
    if (node.translation.size() == 3) m = glm::translate(m, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4)
        m *= glm::mat4_cast(glm::quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2])));
    if (node.scale.size() == 3) m = glm::scale(m, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    return m;
}

}  // namespace

Scene loadGltfScene(const std::filesystem::path& path) {
    const std::string file = path.string();
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string error, warning;
    bool binary = path.extension() == ".glb" || path.extension() == ".GLB";
    bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, file)
                     : loader.LoadASCIIFromFile(&model, &error, &warning, file);
    if (!warning.empty()) log::warn(file, ": ", firstLine(warning));
    if (!ok) throw Error(file + ": cannot load glTF (" + firstLine(error.empty() ? "unknown error" : error) + ")");

    Scene scene;
    scene.name = path.stem().string();
    scene.skyColor = {0.3f, 0.35f, 0.4f};
    for (const tinygltf::Image& image : model.images) {
        TextureData texture;
        texture.name = image.name.empty() ? image.uri : image.name;
        texture.width = image.width;
        texture.height = image.height;
        if (image.width <= 0 || image.height <= 0 || image.component != 4 || image.bits != 8) {
            log::warn(file, ": image '", texture.name, "' is not 8-bit RGBA; replaced by white");
            texture.width = texture.height = 1;
            texture.rgba = {255, 255, 255, 255};
        } else {
            texture.rgba = image.image;
        }
        scene.textures.push_back(std::move(texture));
    }
    auto textureImage = [&](int textureIndex) -> int {
        if (textureIndex < 0 || textureIndex >= int(model.textures.size())) return -1;
        int source = model.textures[textureIndex].source;
        return source >= 0 && source < int(scene.textures.size()) ? source : -1;
    };
    for (const tinygltf::Material& gm : model.materials) {
        Material m;
        m.name = gm.name;
        const auto& pbr = gm.pbrMetallicRoughness;
        m.baseColor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
        float roughness = float(pbr.roughnessFactor);
        m.alpha = std::max(roughness * roughness, 1e-3f);
        m.metallic = float(pbr.metallicFactor);
        if (gm.alphaMode == "MASK") m.alphaCutoff = float(gm.alphaCutoff);
        m.baseColorTexture = textureImage(pbr.baseColorTexture.index);
        if (m.baseColorTexture >= 0) scene.textures[m.baseColorTexture].srgb = true;
        m.metallicRoughnessTexture = textureImage(pbr.metallicRoughnessTexture.index);
        m.normalTexture = textureImage(gm.normalTexture.index);
        m.occlusionTexture = textureImage(gm.occlusionTexture.index);
        if (m.metallicRoughnessTexture >= 0) m.alpha = std::max(m.alpha, 1e-3f);
        scene.materials.push_back(m);
    }
    int defaultMaterial = -1;

    // Each glTF primitive becomes one engine mesh; meshes are instanced by the nodes that reference them.
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> primitivesOfMesh(model.meshes.size());
    for (size_t mi = 0; mi < model.meshes.size(); ++mi) {
        for (const tinygltf::Primitive& primitive : model.meshes[mi].primitives) {
            if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) {
                log::warn(file, ": mesh ", mi, " has a non-triangle primitive; skipped");
                continue;
            }
            auto position = primitive.attributes.find("POSITION");
            if (position == primitive.attributes.end()) throw Error(file + ": primitive without POSITION in mesh " + std::to_string(mi));
            MeshData mesh;
            mesh.name = model.meshes[mi].name;
            mesh.positions = readFloatAccessor<3>(model, position->second, file);
            size_t n = mesh.positions.size();
            if (auto it = primitive.attributes.find("TEXCOORD_0"); it != primitive.attributes.end())
                mesh.uvs = readFloatAccessor<2>(model, it->second, file);
            if (primitive.indices >= 0) mesh.indices = readIndices(model, primitive.indices, file);
            else for (uint32_t i = 0; i < n; ++i) mesh.indices.push_back(i);
            for (uint32_t index : mesh.indices)
                if (index >= n) throw Error(file + ": index out of range in mesh " + std::to_string(mi));
            if (auto it = primitive.attributes.find("NORMAL"); it != primitive.attributes.end())
                mesh.normals = readFloatAccessor<3>(model, it->second, file);
            if (mesh.normals.size() != n) {
                // Flat-ish normals: area-weighted face normals accumulated per vertex.
                mesh.normals.assign(n, glm::vec3(0.0f));
                for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
                    glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]], c = mesh.positions[mesh.indices[i + 2]];
                    glm::vec3 face = glm::cross(b - a, c - a);
                    for (int k = 0; k < 3; ++k) mesh.normals[mesh.indices[i + k]] += face;
                }
                for (glm::vec3& normal : mesh.normals) normal = glm::length(normal) > 0 ? glm::normalize(normal) : glm::vec3(0, 1, 0);
            }
            if (mesh.uvs.size() != n) mesh.uvs.assign(n, glm::vec2(0.0f));
            if (auto it = primitive.attributes.find("TANGENT"); it != primitive.attributes.end())
                mesh.tangents = readFloatAccessor<4>(model, it->second, file);
            if (mesh.tangents.size() != n) generateTangents(mesh);
            int material = primitive.material;
            if (material < 0 || material >= int(scene.materials.size())) {
                if (defaultMaterial < 0) {
                    defaultMaterial = int(scene.materials.size());
                    Material m;
                    m.name = "default";
                    scene.materials.push_back(m);
                }
                material = defaultMaterial;
            }
            primitivesOfMesh[mi].push_back({uint32_t(scene.meshes.size()), uint32_t(material)});
            scene.meshes.push_back(std::move(mesh));
        }
    }

    // Walk the node hierarchy of the default scene (or every root when none is marked).
    std::function<void(int, const glm::mat4&, int)> visit = [&](int nodeIndex, const glm::mat4& parent, int depth) {
        if (nodeIndex < 0 || nodeIndex >= int(model.nodes.size()) || depth > 64) throw Error(file + ": invalid node hierarchy");
        const tinygltf::Node& node = model.nodes[nodeIndex];
        glm::mat4 world = parent * nodeMatrix(node);
        if (node.mesh >= 0 && node.mesh < int(model.meshes.size()))
            for (auto [meshIndex, material] : primitivesOfMesh[node.mesh]) scene.instances.push_back({meshIndex, material, world});
        for (int child : node.children) visit(child, world, depth + 1);
    };
    int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (sceneIndex < int(model.scenes.size())) {
        for (int root : model.scenes[sceneIndex].nodes) visit(root, glm::mat4(1.0f), 0);
    } else {
        for (size_t mi = 0; mi < model.meshes.size(); ++mi)
            for (auto [meshIndex, material] : primitivesOfMesh[mi]) scene.instances.push_back({meshIndex, material, glm::mat4(1.0f)});
    }
    if (scene.instances.empty()) throw Error(file + ": glTF has no mesh to render");

    // A camera framing the scene's bounds and a key light, so any model renders without a scene file.
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Instance& instance : scene.instances)
        for (const glm::vec3& p : scene.meshes[instance.mesh].positions) {
            glm::vec3 w = glm::vec3(instance.transform * glm::vec4(p, 1.0f));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    glm::vec3 center = 0.5f * (lo + hi);
    float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
    Camera camera;
    camera.name = "default";
    camera.target = center;
    camera.position = center + glm::normalize(glm::vec3(0.4f, 0.3f, 1.0f)) * radius * 2.6f;
    camera.nearPlane = radius * 0.01f;
    scene.cameras.push_back(camera);
    scene.lights.push_back({LightType::Directional, glm::normalize(glm::vec3(0.5f, 0.8f, 0.6f)), glm::vec3(1.0f), 3.0f});
    return scene;
}

}  // namespace glimmer
