#include "scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <tuple>

#include "core/error.h"
#include "core/log.h"
#include "scene/uv_transform.h"

namespace glimmer {
namespace {

std::string firstLine(const std::string& text) {
    size_t start = text.find_first_not_of("\r\n ");
    if (start == std::string::npos) return "";
    size_t end = text.find_first_of("\r\n", start);
    return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// What the loader does with each extension a file may use. Anything not listed is ignored with a warning; an
// extension without which the geometry cannot be read at all is refused (rendering would not be meaningful).
enum class ExtensionSupport { Supported, Ignored, Refused };
ExtensionSupport extensionSupport(const std::string& name) {
    static const std::set<std::string> supported = {"KHR_texture_transform", "KHR_mesh_quantization"};
    static const std::set<std::string> refused = {"KHR_draco_mesh_compression", "EXT_meshopt_compression",
                                                  "KHR_meshopt_compression"};
    if (supported.count(name)) return ExtensionSupport::Supported;
    if (refused.count(name)) return ExtensionSupport::Refused;
    return ExtensionSupport::Ignored;
}

// Collects warnings so each distinct one is printed once per file.
class Warnings {
public:
    explicit Warnings(std::string file) : file_(std::move(file)) {}
    void add(const std::string& message) {
        if (seen_.insert(message).second) log::warn(file_, ": ", message);
    }

private:
    std::string file_;
    std::set<std::string> seen_;
};

// Bounds-checked access to the glTF arrays, so a broken index gives a one-line error instead of a crash.
template <class T>
const T& element(const std::vector<T>& array, int index, const char* what, const std::string& file) {
    if (index < 0 || size_t(index) >= array.size())
        throw Error(file + ": " + what + " index " + std::to_string(index) + " out of range (have " +
                    std::to_string(array.size()) + ")");
    return array[size_t(index)];
}

// Reads one component as a float. Normalized integers map to [0,1] / [-1,1] (glTF 3.11); non-normalized
// integers (KHR_mesh_quantization) keep their integer value.
float readComponent(const unsigned char* p, int componentType, bool normalized) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: { float v; std::memcpy(&v, p, 4); return v; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0f : float(p[0]);
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            int8_t s = int8_t(p[0]);
            return normalized ? std::max(s / 127.0f, -1.0f) : float(s);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t s; std::memcpy(&s, p, 2);
            return normalized ? s / 65535.0f : float(s);
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t s; std::memcpy(&s, p, 2);
            return normalized ? std::max(s / 32767.0f, -1.0f) : float(s);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { uint32_t s; std::memcpy(&s, p, 4); return float(s); }
        default: return 0.0f;
    }
}

uint32_t readIndex(const unsigned char* p, int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { uint16_t s; std::memcpy(&s, p, 2); return s; }
        default: { uint32_t s; std::memcpy(&s, p, 4); return s; }
    }
}

// The bytes a buffer view exposes, after checking that the view lies inside its (loaded) buffer.
struct ViewBytes {
    const unsigned char* data = nullptr;
    size_t size = 0;
    size_t stride = 0;
};
ViewBytes viewBytes(const tinygltf::Model& model, int viewIndex, const std::string& file) {
    const tinygltf::BufferView& view = element(model.bufferViews, viewIndex, "bufferView", file);
    const tinygltf::Buffer& buffer = element(model.buffers, view.buffer, "buffer", file);
    if (view.byteOffset + view.byteLength > buffer.data.size())
        throw Error(file + ": bufferView " + std::to_string(viewIndex) + " reads past the end of buffer " +
                    std::to_string(view.buffer) + " (" + std::to_string(buffer.data.size()) + " bytes loaded)");
    return {buffer.data.data() + view.byteOffset, view.byteLength, view.byteStride};
}

// Reads an accessor as N floats per element, applying sparse substitution (glTF 3.6.2.3).
template <int N>
std::vector<glm::vec<N, float>> readFloatAccessor(const tinygltf::Model& model, int index, const std::string& file) {
    using Vec = glm::vec<N, float>;
    const tinygltf::Accessor& accessor = element(model.accessors, index, "accessor", file);
    const std::string name = "accessor " + std::to_string(index);
    int components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
    int componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
    if (components < N || componentSize <= 0) throw Error(file + ": " + name + " has the wrong type");
    size_t elementSize = size_t(components * componentSize);
    std::vector<Vec> out(accessor.count, Vec(0.0f));
    if (accessor.bufferView >= 0) {
        ViewBytes bytes = viewBytes(model, accessor.bufferView, file);
        size_t stride = bytes.stride ? bytes.stride : elementSize;
        if (accessor.count > 0 && accessor.byteOffset + stride * (accessor.count - 1) + elementSize > bytes.size)
            throw Error(file + ": " + name + " reads past its bufferView");
        for (size_t i = 0; i < accessor.count; ++i) {
            const unsigned char* p = bytes.data + accessor.byteOffset + i * stride;
            for (int c = 0; c < N; ++c) out[i][c] = readComponent(p + c * componentSize, accessor.componentType, accessor.normalized);
        }
    }
    if (accessor.sparse.isSparse) {
        size_t count = size_t(std::max(accessor.sparse.count, 0));
        ViewBytes indexBytes = viewBytes(model, accessor.sparse.indices.bufferView, file);
        ViewBytes valueBytes = viewBytes(model, accessor.sparse.values.bufferView, file);
        int indexSize = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.sparse.indices.componentType));
        if (indexSize <= 0 || accessor.sparse.indices.byteOffset + count * size_t(indexSize) > indexBytes.size ||
            accessor.sparse.values.byteOffset + count * elementSize > valueBytes.size)
            throw Error(file + ": sparse data of " + name + " reads past its bufferView");
        for (size_t k = 0; k < count; ++k) {
            uint32_t target = readIndex(indexBytes.data + accessor.sparse.indices.byteOffset + k * indexSize,
                                        accessor.sparse.indices.componentType);
            if (target >= accessor.count) throw Error(file + ": sparse index out of range in " + name);
            const unsigned char* p = valueBytes.data + accessor.sparse.values.byteOffset + k * elementSize;
            for (int c = 0; c < N; ++c)
                out[target][c] = readComponent(p + c * componentSize, accessor.componentType, accessor.normalized);
        }
    }
    return out;
}

std::vector<uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& file) {
    const tinygltf::Accessor& accessor = element(model.accessors, index, "accessor", file);
    const std::string name = "index accessor " + std::to_string(index);
    int size = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.componentType));
    if (accessor.type != TINYGLTF_TYPE_SCALAR || (size != 1 && size != 2 && size != 4) ||
        accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
        throw Error(file + ": " + name + " is not an unsigned integer scalar");
    if (accessor.bufferView < 0 || accessor.sparse.isSparse) {
        // Rare but legal: let the float path handle zero-filled or sparse index data.
        std::vector<uint32_t> out;
        for (const glm::vec1& v : readFloatAccessor<1>(model, index, file)) out.push_back(uint32_t(v.x));
        return out;
    }
    ViewBytes bytes = viewBytes(model, accessor.bufferView, file);
    size_t stride = bytes.stride ? bytes.stride : size_t(size);
    if (accessor.count > 0 && accessor.byteOffset + stride * (accessor.count - 1) + size > bytes.size)
        throw Error(file + ": " + name + " reads past its bufferView");
    std::vector<uint32_t> out(accessor.count);
    for (size_t i = 0; i < accessor.count; ++i) out[i] = readIndex(bytes.data + accessor.byteOffset + i * stride, accessor.componentType);
    return out;
}

glm::mat4 nodeMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::mat4 m;
        for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(node.matrix[i]);  // column-major, as glTF
        return m;
    }
    glm::mat4 m(1.0f);
    if (node.translation.size() == 3) m = glm::translate(m, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    if (node.rotation.size() == 4)  // glTF quaternions are (x, y, z, w); glm::quat takes w first
        m *= glm::mat4_cast(glm::quat(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2])));
    if (node.scale.size() == 3) m = glm::scale(m, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    return m;
}

// Converts a decoded image (1-4 channels, 8 or 16 bits) to 8-bit RGBA. Grey maps to RGB, grey+alpha to RGB+A.
bool toRgba8(const tinygltf::Image& image, std::vector<uint8_t>& rgba) {
    int c = image.component;
    if (image.width <= 0 || image.height <= 0 || c < 1 || c > 4 || (image.bits != 8 && image.bits != 16)) return false;
    size_t pixels = size_t(image.width) * size_t(image.height);
    size_t bytesPerChannel = image.bits / 8;
    if (image.image.size() < pixels * c * bytesPerChannel) return false;
    rgba.resize(pixels * 4);
    for (size_t i = 0; i < pixels; ++i) {
        uint8_t v[4] = {0, 0, 0, 255};
        for (int k = 0; k < c; ++k) {
            size_t at = (i * c + k) * bytesPerChannel;
            // 16-bit samples are stored in host order by stb_image: keep the high byte (rounded).
            if (bytesPerChannel == 1) v[k] = image.image[at];
            else { uint16_t s; std::memcpy(&s, &image.image[at], 2); v[k] = uint8_t((s + 128u) / 257u); }
        }
        uint8_t* out = &rgba[i * 4];
        if (c <= 2) { out[0] = out[1] = out[2] = v[0]; out[3] = c == 2 ? v[1] : 255; }
        else { out[0] = v[0]; out[1] = v[1]; out[2] = v[2]; out[3] = c == 4 ? v[3] : 255; }
    }
    return true;
}

// KHR_texture_transform's offset, rotation and scale as a matrix (uv_transform.h).
glm::mat3 textureTransform(const tinygltf::Value& ext) {
    auto number = [](const tinygltf::Value& v, double fallback) { return v.IsNumber() || v.IsInt() ? v.GetNumberAsDouble() : fallback; };
    glm::vec2 offset(0.0f), scale(1.0f);
    float rotation = 0.0f;
    if (ext.Has("offset") && ext.Get("offset").ArrayLen() == 2)
        offset = {float(number(ext.Get("offset").Get(0), 0)), float(number(ext.Get("offset").Get(1), 0))};
    if (ext.Has("scale") && ext.Get("scale").ArrayLen() == 2)
        scale = {float(number(ext.Get("scale").Get(0), 1)), float(number(ext.Get("scale").Get(1), 1))};
    if (ext.Has("rotation")) rotation = float(number(ext.Get("rotation"), 0));
    return uvTransformMatrix(offset, rotation, scale);
}

bool sameTransform(const glm::mat3& a, const glm::mat3& b) {
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (std::abs(a[c][r] - b[c][r]) > 1e-6f) return false;
    return true;
}

// Turns the glTF model into engine structures. Textures are decoded into Scene::textures on first use; the
// per-texture factors the engine has no slot for (normal scale, occlusion strength) are baked into copies.
class SceneBuilder {
public:
    SceneBuilder(const tinygltf::Model& model, const std::string& file) : model_(model), file_(file), warnings_(file) {}

    Scene build(const std::string& name) {
        checkExtensions();
        scene_.name = name;
        scene_.skyColor = {0.3f, 0.35f, 0.4f};
        for (size_t i = 0; i < model_.materials.size(); ++i) scene_.materials.push_back(material(int(i)));
        buildMeshes();
        walkNodes();
        if (scene_.instances.empty()) throw Error(file_ + ": glTF has no mesh to render");
        addFramingCameraAndLight();
        return std::move(scene_);
    }

    Warnings& warnings() { return warnings_; }

private:
    void checkExtensions() {
        for (const std::string& ext : model_.extensionsRequired)
            if (extensionSupport(ext) == ExtensionSupport::Refused)
                throw Error(file_ + ": requires extension " + ext + ", which Glimmer cannot read");
        for (const std::string& ext : model_.extensionsUsed) {
            if (extensionSupport(ext) != ExtensionSupport::Ignored) continue;
            bool required = std::find(model_.extensionsRequired.begin(), model_.extensionsRequired.end(), ext) !=
                            model_.extensionsRequired.end();
            warnings_.add(std::string("extension ") + ext + (required ? " (marked required)" : "") +
                          " is not supported and is ignored");
        }
        if (!model_.skins.empty()) warnings_.add("skins are ignored (the bind pose is rendered)");
        if (!model_.animations.empty()) warnings_.add("animations are ignored");
    }

    // Index into Scene::textures for glTF texture `textureIndex` as used in a given role; -1 when absent or
    // unusable. normalScale / occlusionStrength other than 1 are baked into a private copy of the image.
    int sceneTexture(int textureIndex, bool srgb, float normalScale = 1.0f, float occlusionStrength = 1.0f) {
        if (textureIndex < 0) return -1;
        const tinygltf::Texture& texture = element(model_.textures, textureIndex, "texture", file_);
        int source = texture.source;
        if (source < 0) {
            warnings_.add("texture " + std::to_string(textureIndex) + " has no source image it can decode; ignored");
            return -1;
        }
        auto key = std::make_tuple(source, srgb, normalScale, occlusionStrength);
        if (auto it = textureCache_.find(key); it != textureCache_.end()) return it->second;
        const tinygltf::Image& image = element(model_.images, source, "image", file_);
        TextureData data;
        data.name = !image.name.empty() ? image.name
                    : !image.uri.empty() && image.uri.rfind("data:", 0) != 0 ? image.uri
                                                                             : "image " + std::to_string(source);
        data.srgb = srgb;
        if (!toRgba8(image, data.rgba)) {
            warnings_.add(data.name + " has no decoded pixels; textures using it are ignored");
            textureCache_[key] = -1;
            return -1;
        }
        data.width = image.width;
        data.height = image.height;
        if (normalScale != 1.0f) {
            // glTF 3.9.3: scaledNormal = normalize((sample * 2 - 1) * vec3(scale, scale, 1)), baked per texel.
            for (size_t i = 0; i + 3 < data.rgba.size(); i += 4) {
                glm::vec3 n = glm::vec3(data.rgba[i], data.rgba[i + 1], data.rgba[i + 2]) / 127.5f - 1.0f;
                n = glm::vec3(n.x * normalScale, n.y * normalScale, n.z);
                n = glm::length(n) > 1e-6f ? glm::normalize(n) : glm::vec3(0, 0, 1);
                for (int k = 0; k < 3; ++k) data.rgba[i + k] = uint8_t(std::clamp(std::lround((n[k] + 1.0f) * 127.5f), 0L, 255L));
            }
        }
        if (occlusionStrength != 1.0f) {
            // glTF 3.9.3: occluded = lerp(colour, colour * sample, strength); the red channel holds occlusion.
            for (size_t i = 0; i + 3 < data.rgba.size(); i += 4) {
                float o = 1.0f + occlusionStrength * (data.rgba[i] / 255.0f - 1.0f);
                data.rgba[i] = uint8_t(std::clamp(std::lround(o * 255.0f), 0L, 255L));
            }
        }
        int index = int(scene_.textures.size());
        scene_.textures.push_back(std::move(data));
        textureCache_[key] = index;
        return index;
    }

    Material material(int index) {
        const tinygltf::Material& gm = model_.materials[size_t(index)];
        Material m;
        m.name = gm.name.empty() ? "material" + std::to_string(index) : gm.name;
        const auto& pbr = gm.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() == 4)
            m.baseColor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
        float roughness = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
        m.alpha = std::max(roughness * roughness, 1e-3f);  // the G-buffer multiplies by the texture's roughness^2
        m.metallic = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
        m.doubleSided = gm.doubleSided;   // glTF 2.0 Sec. 3.9.5: single-sided (back faces culled) unless set
        if (gm.alphaMode == "MASK") m.alphaCutoff = float(gm.alphaCutoff);
        if (gm.alphaMode == "BLEND") {
            // The deferred pipeline has no blending: the closest meaningful rendering is a mask at one half.
            warnings_.add("material '" + m.name + "': alphaMode BLEND is rendered as MASK with cutoff 0.5");
            m.alphaCutoff = 0.5f;
        }
        if (gm.emissiveTexture.index >= 0 ||
            (gm.emissiveFactor.size() == 3 && (gm.emissiveFactor[0] > 0 || gm.emissiveFactor[1] > 0 || gm.emissiveFactor[2] > 0)))
            warnings_.add("material '" + m.name + "': emission is not rendered");

        // One UV transform per material (the engine applies Material::uvTransform to every texture lookup).
        // The base colour's transform wins; a texture with a different transform or another UV set is dropped.
        struct Slot { const char* role; int gltfTexture; int texCoord; const tinygltf::ExtensionMap* extensions; int* target;
                      bool srgb; float normalScale; float occlusionStrength; };
        std::vector<Slot> slots = {
            {"baseColor", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, &pbr.baseColorTexture.extensions, &m.baseColorTexture, true, 1, 1},
            {"normal", gm.normalTexture.index, gm.normalTexture.texCoord, &gm.normalTexture.extensions, &m.normalTexture, false, float(gm.normalTexture.scale), 1},
            {"metallicRoughness", pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, &pbr.metallicRoughnessTexture.extensions, &m.metallicRoughnessTexture, false, 1, 1},
            {"occlusion", gm.occlusionTexture.index, gm.occlusionTexture.texCoord, &gm.occlusionTexture.extensions, &m.occlusionTexture, false, 1, float(gm.occlusionTexture.strength)},
        };
        bool haveTransform = false;
        for (const Slot& slot : slots) {
            if (slot.gltfTexture < 0) continue;
            glm::mat3 transform(1.0f);
            int texCoord = slot.texCoord;
            if (auto it = slot.extensions->find("KHR_texture_transform"); it != slot.extensions->end()) {
                transform = textureTransform(it->second);
                if (it->second.Has("texCoord") && it->second.Get("texCoord").IsInt()) texCoord = it->second.Get("texCoord").GetNumberAsInt();
            }
            std::string what = "material '" + m.name + "': " + slot.role + " texture";
            if (texCoord != 0) {
                warnings_.add(what + " uses TEXCOORD_" + std::to_string(texCoord) + " (only TEXCOORD_0 is supported); ignored");
                continue;
            }
            if (!haveTransform) {
                m.uvTransform = transform;
                haveTransform = true;
            } else if (!sameTransform(transform, m.uvTransform)) {
                warnings_.add(what + " has a KHR_texture_transform different from the material's other textures "
                                     "(one transform per material is supported); ignored");
                continue;
            }
            *slot.target = sceneTexture(slot.gltfTexture, slot.srgb, slot.normalScale, slot.occlusionStrength);
        }
        return m;
    }

    int defaultMaterial() {
        if (defaultMaterial_ < 0) {
            defaultMaterial_ = int(scene_.materials.size());
            Material m;
            m.name = "default";
            m.alpha = 0.25f;
            scene_.materials.push_back(m);
        }
        return defaultMaterial_;
    }

    // Each distinct glTF primitive geometry (same attribute and index accessors) becomes one engine mesh;
    // primitives that differ only in material share it, and nodes instance it.
    void buildMeshes() {
        using GeometryKey = std::tuple<int, int, int, int, int>;  // POSITION, NORMAL, TANGENT, TEXCOORD_0, indices
        std::map<GeometryKey, uint32_t> meshOfGeometry;
        primitivesOfMesh_.resize(model_.meshes.size());
        for (size_t mi = 0; mi < model_.meshes.size(); ++mi) {
            for (const tinygltf::Primitive& primitive : model_.meshes[mi].primitives) {
                if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) {
                    warnings_.add("mesh " + std::to_string(mi) + " has a primitive that is not a triangle list; skipped");
                    continue;
                }
                auto attribute = [&](const char* name) {
                    auto it = primitive.attributes.find(name);
                    return it == primitive.attributes.end() ? -1 : it->second;
                };
                if (attribute("POSITION") < 0)
                    throw Error(file_ + ": primitive without POSITION in mesh " + std::to_string(mi));
                if (!primitive.targets.empty()) warnings_.add("morph targets are ignored");
                GeometryKey key{attribute("POSITION"), attribute("NORMAL"), attribute("TANGENT"), attribute("TEXCOORD_0"), primitive.indices};
                auto found = meshOfGeometry.find(key);
                uint32_t meshIndex;
                if (found != meshOfGeometry.end()) {
                    meshIndex = found->second;
                } else {
                    meshIndex = uint32_t(scene_.meshes.size());
                    scene_.meshes.push_back(readPrimitive(primitive, model_.meshes[mi].name, int(mi)));
                    meshOfGeometry[key] = meshIndex;
                }
                int material = primitive.material;
                if (material < 0 || material >= int(scene_.materials.size())) {
                    if (material >= 0) warnings_.add("a primitive names material " + std::to_string(material) + ", which does not exist; default used");
                    material = defaultMaterial();
                }
                primitivesOfMesh_[mi].push_back({meshIndex, uint32_t(material)});
            }
        }
    }

    MeshData readPrimitive(const tinygltf::Primitive& primitive, const std::string& name, int meshIndex) {
        MeshData mesh;
        mesh.name = name.empty() ? "mesh" + std::to_string(meshIndex) : name;
        mesh.positions = readFloatAccessor<3>(model_, primitive.attributes.at("POSITION"), file_);
        size_t n = mesh.positions.size();
        auto optional = [&](const char* attribute, auto& target, auto reader) {
            auto it = primitive.attributes.find(attribute);
            if (it == primitive.attributes.end()) return;
            target = reader(model_, it->second, file_);
            if (target.size() != n) {
                warnings_.add(std::string(attribute) + " of mesh " + std::to_string(meshIndex) + " has the wrong count; regenerated");
                target.clear();
            }
        };
        optional("TEXCOORD_0", mesh.uvs, readFloatAccessor<2>);
        optional("NORMAL", mesh.normals, readFloatAccessor<3>);
        optional("TANGENT", mesh.tangents, readFloatAccessor<4>);
        if (primitive.indices >= 0) {
            mesh.indices = readIndices(model_, primitive.indices, file_);
        } else {
            for (uint32_t i = 0; i < n; ++i) mesh.indices.push_back(i);
        }
        mesh.indices.resize(mesh.indices.size() / 3 * 3);
        for (uint32_t index : mesh.indices)
            if (index >= n) throw Error(file_ + ": vertex index " + std::to_string(index) + " out of range in mesh " + std::to_string(meshIndex));
        for (const glm::vec3& p : mesh.positions)
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw Error(file_ + ": non-finite vertex position in mesh " + std::to_string(meshIndex));
        if (mesh.normals.empty()) {
            // glTF 3.7.2.1: without normals, flat normals are expected. Area-weighted vertex normals are a
            // smooth approximation that needs no vertex splitting.
            mesh.normals.assign(n, glm::vec3(0.0f));
            for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
                glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]], c = mesh.positions[mesh.indices[i + 2]];
                glm::vec3 face = glm::cross(b - a, c - a);
                for (int k = 0; k < 3; ++k) mesh.normals[mesh.indices[i + k]] += face;
            }
        }
        for (glm::vec3& normal : mesh.normals) normal = glm::length(normal) > 1e-20f ? glm::normalize(normal) : glm::vec3(0, 1, 0);
        if (mesh.uvs.empty()) mesh.uvs.assign(n, glm::vec2(0.0f));
        if (!mesh.tangents.empty()) {
            // Authored tangents are often not quite orthogonal to the normals (older exporters): Gram-Schmidt
            // them, keep the handedness, and regenerate the mesh's frames if any tangent is unusable.
            for (size_t v = 0; v < n && !mesh.tangents.empty(); ++v) {
                glm::vec3 normal = mesh.normals[v], t = glm::vec3(mesh.tangents[v]);
                t -= normal * glm::dot(normal, t);
                if (!(glm::dot(t, t) > 1e-12f)) {
                    warnings_.add("mesh " + std::to_string(meshIndex) + " has degenerate TANGENTs; regenerated from UVs");
                    mesh.tangents.clear();
                    break;
                }
                mesh.tangents[v] = glm::vec4(glm::normalize(t), mesh.tangents[v].w < 0.0f ? -1.0f : 1.0f);
            }
        }
        if (mesh.tangents.empty()) generateTangents(mesh);
        return mesh;
    }

    void walkNodes() {
        // The default scene (or scene 0); a file without scenes shows every mesh once at the origin.
        std::vector<bool> onPath(model_.nodes.size(), false);
        std::function<void(int, const glm::mat4&, int)> visit = [&](int nodeIndex, const glm::mat4& parent, int depth) {
            const tinygltf::Node& node = element(model_.nodes, nodeIndex, "node", file_);
            if (onPath[size_t(nodeIndex)] || depth > 256)
                throw Error(file_ + ": node hierarchy has a cycle at node " + std::to_string(nodeIndex));
            onPath[size_t(nodeIndex)] = true;
            glm::mat4 world = parent * nodeMatrix(node);
            if (node.mesh >= 0) {
                element(model_.meshes, node.mesh, "mesh", file_);
                for (auto [meshIndex, material] : primitivesOfMesh_[size_t(node.mesh)])
                    scene_.instances.push_back({meshIndex, material, world});
            }
            if (node.camera >= 0) addCamera(element(model_.cameras, node.camera, "camera", file_), node, world);
            for (int child : node.children) visit(child, world, depth + 1);
            onPath[size_t(nodeIndex)] = false;
        };
        int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
        if (sceneIndex < int(model_.scenes.size())) {
            for (int root : model_.scenes[size_t(sceneIndex)].nodes) visit(root, glm::mat4(1.0f), 0);
        } else {
            for (size_t mi = 0; mi < model_.meshes.size(); ++mi)
                for (auto [meshIndex, material] : primitivesOfMesh_[mi]) scene_.instances.push_back({meshIndex, material, glm::mat4(1.0f)});
        }
    }

    // glTF cameras look down their local -Z with +Y up (glTF 3.10.1). Orthographic ones are skipped.
    void addCamera(const tinygltf::Camera& gc, const tinygltf::Node& node, const glm::mat4& world) {
        if (gc.type != "perspective") {
            warnings_.add("orthographic cameras are not supported; skipped");
            return;
        }
        Camera camera;
        camera.name = !gc.name.empty() ? gc.name : !node.name.empty() ? node.name : "camera" + std::to_string(gltfCameras_.size());
        camera.position = glm::vec3(world[3]);
        glm::vec3 forward = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
        camera.target = camera.position + forward;
        camera.up = glm::normalize(glm::vec3(world * glm::vec4(0, 1, 0, 0)));
        if (gc.perspective.yfov > 0) camera.verticalFovDegrees = float(glm::degrees(gc.perspective.yfov));
        if (gc.perspective.znear > 0) camera.nearPlane = float(gc.perspective.znear);
        gltfCameras_.push_back(camera);
    }

    // A camera framing the scene's bounds (first, the default) and a key light, so any model renders without a
    // scene file. The file's own cameras follow under their names.
    void addFramingCameraAndLight() {
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const Instance& instance : scene_.instances)
            for (const glm::vec3& p : scene_.meshes[instance.mesh].positions) {
                glm::vec3 w = glm::vec3(instance.transform * glm::vec4(p, 1.0f));
                lo = glm::min(lo, w);
                hi = glm::max(hi, w);
            }
        glm::vec3 center = 0.5f * (lo + hi);
        float radius = std::max(0.5f * glm::length(hi - lo), 1e-4f);
        Camera camera;
        camera.name = "default";
        camera.target = center;
        camera.position = center + glm::normalize(glm::vec3(0.4f, 0.3f, 1.0f)) * radius * 2.6f;
        camera.nearPlane = radius * 0.01f;
        scene_.cameras.push_back(camera);
        std::set<std::string> names = {"default"};
        for (Camera c : gltfCameras_) {
            std::string base = c.name;
            for (int k = 2; names.count(c.name); ++k) c.name = base + "_" + std::to_string(k);
            names.insert(c.name);
            scene_.cameras.push_back(c);
        }
        // Key light above and to the right; a weaker fill from just beside the default camera, so metals (which
        // have no diffuse term and, without an environment, no ambient) still show their highlights.
        scene_.lights.push_back({LightType::Directional, glm::normalize(glm::vec3(0.5f, 0.8f, 0.6f)), glm::vec3(1.0f), 3.0f});
        glm::vec3 towardCamera = glm::normalize(camera.position - center);
        scene_.lights.push_back({LightType::Directional, glm::normalize(towardCamera + glm::vec3(-0.3f, 0.25f, 0.0f)),
                                 glm::vec3(1.0f), 1.0f});
    }

    const tinygltf::Model& model_;
    std::string file_;
    Warnings warnings_;
    Scene scene_;
    std::map<std::tuple<int, bool, float, float>, int> textureCache_;
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> primitivesOfMesh_;
    std::vector<Camera> gltfCameras_;
    int defaultMaterial_ = -1;
};

// Decodes with tinygltf's own loader, but turns a failure into a warning (the image stays empty and textures
// using it are ignored) instead of failing the whole file: e.g. KTX2 / WebP images of KHR_texture_basisu or
// EXT_texture_webp, which tinygltf cannot decode, leave a model that still renders meaningfully.
bool tolerantImageLoader(tinygltf::Image* image, const int index, std::string* error, std::string* warning, int width,
                         int height, const unsigned char* bytes, int size, void*) {
    std::string decodeError;
    if (tinygltf::LoadImageData(image, index, &decodeError, warning, width, height, bytes, size, nullptr)) return true;
    if (warning) *warning += "image " + std::to_string(index) + " could not be decoded (" + firstLine(decodeError) + ")\n";
    image->width = image->height = 0;
    image->image.clear();
    (void)error;
    return true;
}

}  // namespace

Scene loadGltfScene(const std::filesystem::path& path) {
    const std::string file = path.string();
    if (!std::filesystem::is_regular_file(path)) throw Error(file + ": glTF file not found");
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(tolerantImageLoader, nullptr);
    tinygltf::Model model;
    std::string error, warning;
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    bool ok = false;
    try {
        ok = ext == ".glb" ? loader.LoadBinaryFromFile(&model, &error, &warning, file)
                           : loader.LoadASCIIFromFile(&model, &error, &warning, file);
    } catch (const std::exception& e) {
        throw Error(file + ": cannot load glTF (" + firstLine(e.what()) + ")");
    }
    if (!ok) throw Error(file + ": cannot load glTF (" + firstLine(error.empty() ? "unknown error" : error) + ")");
    SceneBuilder builder(model, file);
    // tinygltf reports missing images and similar non-fatal problems as warnings, one per line.
    for (size_t start = 0; start < warning.size();) {
        size_t end = warning.find('\n', start);
        std::string line = firstLine(warning.substr(start, end == std::string::npos ? std::string::npos : end - start));
        if (!line.empty()) builder.warnings().add(line);
        if (end == std::string::npos) break;
        start = end + 1;
    }
    try {
        return builder.build(path.stem().string());
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(file + ": invalid glTF (" + firstLine(e.what()) + ")");
    }
}

}  // namespace glimmer
