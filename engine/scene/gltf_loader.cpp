#include "scene/gltf_loader.h"

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "core/error.h"
#include "core/files.h"
#include "core/image_io.h"
#include "core/log.h"
#include "scene/gltf_area_lights.h"
#include "scene/gltf_glint_material.h"
#include "scene/gltf_json.h"
#include "scene/scene_limits.h"
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
    static const std::set<std::string> supported = {"KHR_texture_transform", "KHR_mesh_quantization",
                                                    "KHR_materials_emissive_strength", "KHR_lights_punctual",
                                                    "KHR_materials_clearcoat", "GLIMMER_materials_glint",
                                                    "GLIMMER_lights_area"};
    static const std::set<std::string> refused = {"KHR_draco_mesh_compression", "EXT_meshopt_compression",
                                                  "KHR_meshopt_compression"};
    if (supported.count(name)) return ExtensionSupport::Supported;
    if (refused.count(name)) return ExtensionSupport::Refused;
    return ExtensionSupport::Ignored;
}

// The first required extension the loader refuses, read from the file's JSON (the JSON chunk of a GLB), or "".
// tinygltf fails on compressed geometry before the extension list can be checked (a Draco primitive's accessors
// have no bufferView), so a failed load asks this to name the real reason.
std::string refusedRequiredExtension(const std::vector<unsigned char>& bytes, bool binary) {
    const unsigned char* json = bytes.data();
    size_t length = bytes.size();
    if (binary) {
        if (bytes.size() < 20) return "";
        uint32_t chunkLength = 0;
        std::memcpy(&chunkLength, bytes.data() + 12, 4);
        if (chunkLength > bytes.size() - 20) return "";
        json = bytes.data() + 20;
        length = chunkLength;
    }
    nlohmann::json root = nlohmann::json::parse(json, json + length, nullptr, false);
    if (!root.is_object() || !root.contains("extensionsRequired") || !root["extensionsRequired"].is_array()) return "";
    for (const auto& ext : root["extensionsRequired"])
        if (ext.is_string() && extensionSupport(ext.get<std::string>()) == ExtensionSupport::Refused)
            return ext.get<std::string>();
    return "";
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

// offset + (count - 1) * stride + elementSize <= size, in 64-bit arithmetic that cannot wrap: offsets near 2^64
// in a hostile file must fail the check, not pass it modulo 2^64. count == 0 needs only offset <= size.
bool rangeFits(uint64_t offset, uint64_t count, uint64_t stride, uint64_t elementSize, uint64_t size) {
    if (offset > size) return false;
    if (count == 0) return true;
    uint64_t span = 0, end = 0;
    if (__builtin_mul_overflow(count - 1, stride, &span) || __builtin_add_overflow(span, elementSize, &span) ||
        __builtin_add_overflow(offset, span, &end))
        return false;
    return end <= size;
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
    if (!rangeFits(view.byteOffset, 1, 0, view.byteLength, buffer.data.size()))
        throw Error(file + ": bufferView " + std::to_string(viewIndex) + " reads past the end of buffer " +
                    std::to_string(view.buffer) + " (byteOffset " + std::to_string(view.byteOffset) + " + byteLength " +
                    std::to_string(view.byteLength) + " > " + std::to_string(buffer.data.size()) + " bytes loaded)");
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
    // Every size is checked against the bytes that hold it before anything is allocated.
    uint64_t limit = accessor.bufferView >= 0 ? kMaxAccessorElements : kMaxZeroAccessorElements;
    if (accessor.count > limit)
        throw Error(file + ": " + name + ": count " + std::to_string(accessor.count) + " exceeds the limit " + std::to_string(limit));
    ViewBytes bytes;
    size_t stride = elementSize;
    if (accessor.bufferView >= 0) {
        bytes = viewBytes(model, accessor.bufferView, file);
        stride = bytes.stride ? bytes.stride : elementSize;
        if (!rangeFits(accessor.byteOffset, accessor.count, stride, elementSize, bytes.size))
            throw Error(file + ": " + name + ": byteOffset " + std::to_string(accessor.byteOffset) + " and count " +
                        std::to_string(accessor.count) + " read past its bufferView (" + std::to_string(bytes.size) + " bytes)");
    }
    std::vector<Vec> out(accessor.count, Vec(0.0f));
    if (accessor.bufferView >= 0) {
        for (size_t i = 0; i < accessor.count; ++i) {
            const unsigned char* p = bytes.data + accessor.byteOffset + i * stride;
            for (int c = 0; c < N; ++c) out[i][c] = readComponent(p + c * componentSize, accessor.componentType, accessor.normalized);
        }
    }
    if (accessor.sparse.isSparse) {
        if (accessor.sparse.count < 0 || uint64_t(accessor.sparse.count) > accessor.count ||
            accessor.sparse.indices.byteOffset < 0 || accessor.sparse.values.byteOffset < 0)
            throw Error(file + ": sparse data of " + name + ": count or byteOffset out of range");
        size_t count = size_t(accessor.sparse.count);
        ViewBytes indexBytes = viewBytes(model, accessor.sparse.indices.bufferView, file);
        ViewBytes valueBytes = viewBytes(model, accessor.sparse.values.bufferView, file);
        int indexSize = tinygltf::GetComponentSizeInBytes(uint32_t(accessor.sparse.indices.componentType));
        if (indexSize <= 0 || accessor.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
            !rangeFits(uint64_t(accessor.sparse.indices.byteOffset), count, uint64_t(indexSize), uint64_t(indexSize), indexBytes.size) ||
            !rangeFits(uint64_t(accessor.sparse.values.byteOffset), count, elementSize, elementSize, valueBytes.size))
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
    if (accessor.count > kMaxAccessorElements)
        throw Error(file + ": " + name + ": count " + std::to_string(accessor.count) + " exceeds the limit " +
                    std::to_string(kMaxAccessorElements));
    ViewBytes bytes = viewBytes(model, accessor.bufferView, file);
    size_t stride = bytes.stride ? bytes.stride : size_t(size);
    if (!rangeFits(accessor.byteOffset, accessor.count, stride, uint64_t(size), bytes.size))
        throw Error(file + ": " + name + ": byteOffset " + std::to_string(accessor.byteOffset) + " and count " +
                    std::to_string(accessor.count) + " read past its bufferView (" + std::to_string(bytes.size) + " bytes)");
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

// KHR_texture_transform's offset, rotation and scale as a matrix (uv_transform.h), from the file's JSON: a null, a
// wrong type or a wrong length is an error naming the key (tinygltf's values wrapped wide integers).
glm::mat3 textureTransform(const GltfValue& ext, const GltfValueReader& r, int& texCoord) {
    constexpr double kLimit = 1e9;
    glm::vec2 offset(0.0f), scale(1.0f);
    float rotation = 0.0f;
    if (const GltfValue* v = jsonMember(&ext, "offset")) {
        std::vector<double> o = r.numbers(*v, "offset", 2, -kLimit, kLimit);
        offset = {float(o[0]), float(o[1])};
    }
    if (const GltfValue* v = jsonMember(&ext, "scale")) {
        std::vector<double> k = r.numbers(*v, "scale", 2, -kLimit, kLimit);
        scale = {float(k[0]), float(k[1])};
    }
    if (const GltfValue* v = jsonMember(&ext, "rotation")) rotation = float(r.number(*v, "rotation", -kLimit, kLimit));
    if (const GltfValue* v = jsonMember(&ext, "texCoord")) texCoord = int(r.integer(*v, "texCoord", 0, 1 << 16));
    return uvTransformMatrix(offset, rotation, scale);
}

// glTF 3.8.3 sampler of a texture: wrap modes (default REPEAT) and whether the minification filter reads mipmaps
// (default: yes; NEAREST and LINEAR read level 0 only). Unknown enum values keep the default with a warning.
TextureSampler textureSampler(const tinygltf::Model& model, const tinygltf::Texture& texture, const std::string& file,
                              const std::function<void(const std::string&)>& warn) {
    TextureSampler out;
    if (texture.sampler < 0) return out;
    const tinygltf::Sampler& sampler = element(model.samplers, texture.sampler, "sampler", file);
    auto wrap = [&](int mode, const char* axis) {
        switch (mode) {
            case -1: case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::Repeat;
            case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
            case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
            default:
                warn("samplers[" + std::to_string(texture.sampler) + "]." + axis + " " + std::to_string(mode) +
                     " is not a wrap mode; REPEAT used");
                return TextureWrap::Repeat;
        }
    };
    out.wrapS = wrap(sampler.wrapS, "wrapS");
    out.wrapT = wrap(sampler.wrapT, "wrapT");
    out.mipmaps = sampler.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST && sampler.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR;
    out.nearestMag = sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
    return out;
}

int samplerKey(const TextureSampler& s) {
    return int(s.wrapS) | int(s.wrapT) << 2 | int(s.mipmaps) << 4 | int(s.nearestMag) << 5;
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
    SceneBuilder(const tinygltf::Model& model, const GltfValue& json, const std::string& file)
        : model_(model), json_(json), file_(file), warnings_(file) {}

    Scene build(const std::string& name) {
        // glTF 1.0 files parse into nonsense under the 2.0 schema: refuse them by name (glTF 3.3 asset.version).
        if (model_.asset.version.rfind("2.", 0) != 0)
            throw Error(file_ + ": asset.version '" + model_.asset.version + "' is not glTF 2.x");
        if (!model_.asset.minVersion.empty() && model_.asset.minVersion.rfind("2.0", 0) != 0)
            throw Error(file_ + ": asset.minVersion '" + model_.asset.minVersion + "' is newer than glTF 2.0");
        if (model_.nodes.size() > kMaxNodes)
            throw Error(file_ + ": nodes: " + std::to_string(model_.nodes.size()) + " nodes exceed the limit " + std::to_string(kMaxNodes));
        checkExtensions();
        scene_.name = name;
        scene_.skyColor = {0.3f, 0.35f, 0.4f};
        for (size_t i = 0; i < model_.materials.size(); ++i) scene_.materials.push_back(material(int(i)));
        buildMeshes();
        walkNodes();
        if (scene_.instances.empty())
            throw Error(file_ + ": glTF has no mesh to render" + (skippedInstances_ ? " (every instance has a singular or out-of-range transform)" : ""));
        measureSurfacePerUvArea(scene_);
        addFramingCameraAndLight();
        return std::move(scene_);
    }

    Warnings& warnings() { return warnings_; }
    // What tinygltf reported about an external image file it could not read (path or URI -> reason), so that the
    // one warning of a texture without pixels can name the file and say why instead of tinygltf's raw lines.
    void setImageFileProblems(std::vector<std::pair<std::string, std::string>> problems) { imageFileProblems_ = std::move(problems); }

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
        TextureSampler sampler = textureSampler(model_, texture, file_, [this](const std::string& m) { warnings_.add(m); });
        auto key = std::make_tuple(source, srgb, normalScale, occlusionStrength, samplerKey(sampler));
        if (auto it = textureCache_.find(key); it != textureCache_.end()) return it->second;
        const tinygltf::Image& image = element(model_.images, source, "image", file_);
        TextureData data;
        data.sampler = sampler;
        data.name = !image.name.empty() ? image.name
                    : !image.uri.empty() && image.uri.rfind("data:", 0) != 0 ? image.uri
                                                                             : "image " + std::to_string(source);
        data.srgb = srgb;
        if (!toRgba8(image, data.rgba)) {
            warnings_.add(imageProblem(image, source));
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

    // One line for an image without pixels: its file (or index) and the reason.
    std::string imageProblem(const tinygltf::Image& image, int source) const {
        const bool external = !image.uri.empty() && image.uri.rfind("data:", 0) != 0;
        const std::string what = external ? "image file '" + image.uri + "' (images[" + std::to_string(source) + "])"
                                          : "images[" + std::to_string(source) + "]";
        if (external) {
            auto endsWith = [](const std::string& text, const std::string& tail) {
                return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
            };
            for (const auto& [path, reason] : imageFileProblems_)
                if (endsWith(path, image.uri) || endsWith(image.uri, path)) return what + " " + reason + "; textures using it are ignored";
        }
        return what + " has no decoded pixels; textures using it are ignored";
    }

    Material material(int index) {
        const tinygltf::Material& gm = model_.materials[size_t(index)];
        Material m;
        m.name = gm.name.empty() ? "material" + std::to_string(index) : gm.name;
        const auto& pbr = gm.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() == 4) {
            // glTF 3.9.2: each factor lies in [0, 1]. Outside it (negative, huge, NaN) the image is meaningless.
            for (int c = 0; c < 4; ++c)
                if (!(pbr.baseColorFactor[size_t(c)] >= -1e-3 && pbr.baseColorFactor[size_t(c)] <= 1.001))
                    throw Error(file_ + ": materials[" + std::to_string(index) + "].pbrMetallicRoughness.baseColorFactor[" +
                                std::to_string(c) + "] = " + std::to_string(pbr.baseColorFactor[size_t(c)]) + " is outside [0, 1]");
            m.baseColor = glm::clamp(glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]),
                                     glm::vec4(0.0f), glm::vec4(1.0f));
        }
        float roughness = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
        m.alpha = std::max(roughness * roughness, 1e-3f);  // the G-buffer multiplies by the texture's roughness^2
        m.metallic = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
        m.doubleSided = gm.doubleSided;   // glTF 2.0 Sec. 3.9.5: single-sided (back faces culled) unless set
        const GltfValue* raw = jsonElement(jsonMember(&json_, "materials"), size_t(index));
        const GltfValueReader reader(file_ + ": materials[" + std::to_string(index) + "].");
        if (const GltfValue* cutoff = jsonMember(raw, "alphaCutoff")) {
            // glTF 3.9.4: alphaCutoff >= 0 (default 0.5); above 1 a MASK material would vanish whatever its alpha.
            double value = reader.number(*cutoff, "alphaCutoff", 0.0, gm.alphaMode == "MASK" ? 1.0 : 1e30);
            if (gm.alphaMode == "MASK") m.alphaCutoff = float(value);
        } else if (gm.alphaMode == "MASK") {
            m.alphaCutoff = 0.5f;
        }
        m.blend = gm.alphaMode == "BLEND";   // composited after lighting by the transparent pass
        m.emissive = emission(gm, raw, reader);
        ClearcoatTextures coat = clearcoat(raw, reader, m);

        // One UV transform per material (the engine applies Material::uvTransform to every texture lookup).
        // The base colour's transform wins; a texture with a different transform or another UV set is dropped.
        struct Slot { const char* role; int gltfTexture; int texCoord; const GltfValue* info; std::string key; int* target;
                      bool srgb; float normalScale; float occlusionStrength; };
        const GltfValue* rawPbr = jsonMember(raw, "pbrMetallicRoughness");
        const std::string coatKey = "extensions.KHR_materials_clearcoat.";
        std::vector<Slot> slots = {
            {"baseColor", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, jsonMember(rawPbr, "baseColorTexture"), "pbrMetallicRoughness.baseColorTexture", &m.baseColorTexture, true, 1, 1},
            {"normal", gm.normalTexture.index, gm.normalTexture.texCoord, jsonMember(raw, "normalTexture"), "normalTexture", &m.normalTexture, false, float(gm.normalTexture.scale), 1},
            {"metallicRoughness", pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, jsonMember(rawPbr, "metallicRoughnessTexture"), "pbrMetallicRoughness.metallicRoughnessTexture", &m.metallicRoughnessTexture, false, 1, 1},
            {"occlusion", gm.occlusionTexture.index, gm.occlusionTexture.texCoord, jsonMember(raw, "occlusionTexture"), "occlusionTexture", &m.occlusionTexture, false, 1, float(gm.occlusionTexture.strength)},
            {"emissive", gm.emissiveTexture.index, gm.emissiveTexture.texCoord, jsonMember(raw, "emissiveTexture"), "emissiveTexture", &m.emissiveTexture, true, 1, 1},
            {"clearcoat", coat.factor.index, coat.factor.texCoord, coat.factor.info, coatKey + "clearcoatTexture", &m.clearcoatTexture, false, 1, 1},
            {"clearcoatRoughness", coat.roughness.index, coat.roughness.texCoord, coat.roughness.info, coatKey + "clearcoatRoughnessTexture", &m.clearcoatRoughnessTexture, false, 1, 1},
            {"clearcoatNormal", coat.normal.index, coat.normal.texCoord, coat.normal.info, coatKey + "clearcoatNormalTexture", &m.clearcoatNormalTexture, false, coat.normal.scale, 1},
        };
        bool haveTransform = false;
        for (const Slot& slot : slots) {
            if (slot.gltfTexture < 0) continue;
            glm::mat3 transform(1.0f);
            int texCoord = slot.texCoord;
            if (const GltfValue* ext = jsonMember(jsonMember(slot.info, "extensions"), "KHR_texture_transform"))
                transform = textureTransform(*ext, GltfValueReader(reader.prefix() + slot.key + ".extensions.KHR_texture_transform."), texCoord);
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
        if (gm.emissiveTexture.index >= 0 && m.emissiveTexture < 0 && m.emissive != glm::vec3(0.0f)) {
            // emissiveFactor multiplies the texture (glTF 3.9.2): alone it would light the whole surface. One
            // line per model, whatever the number of materials.
            m.emissive = glm::vec3(0.0f);
            warnings_.add("emission is off on materials whose emissive texture cannot be used");
        }
        // GLIMMER_materials_glint or its extras form (gltf_glint_material.h); its density texture is linear.
        readGlintMaterial(raw, m, file_,
                          [&](int t) { return t >= 0 && size_t(t) < model_.textures.size() ? sceneTexture(t, false) : -2; },
                          [&](const std::string& w) { warnings_.add(w); });
        return m;
    }

    // A textureInfo / normalTextureInfo read from an extension's JSON (tinygltf parses only the core ones).
    struct ExtensionTexture {
        int index = -1;
        int texCoord = 0;
        float scale = 1.0f;
        const GltfValue* info = nullptr;   // its JSON object (for KHR_texture_transform)
    };
    struct ClearcoatTextures { ExtensionTexture factor, roughness, normal; };

    // KHR_materials_clearcoat: clearcoatFactor and clearcoatRoughnessFactor (numbers in [0, 1], default 0) into
    // the material; its three textures are returned for the material's texture slots. A factor outside [0, 1],
    // a null, a wrong type or a texture that is not a textureInfo object is an error naming the key.
    ClearcoatTextures clearcoat(const GltfValue* material, const GltfValueReader& reader, Material& m) {
        ClearcoatTextures coat;
        const GltfValue* ext = jsonMember(jsonMember(material, "extensions"), "KHR_materials_clearcoat");
        if (!ext) return coat;
        const GltfValueReader r(reader.prefix() + "extensions.KHR_materials_clearcoat.");
        if (!ext->is_object()) reader.fail("extensions.KHR_materials_clearcoat", "expected an object, not " + jsonValueText(*ext));
        auto factor = [&](const char* key) {
            const GltfValue* v = jsonMember(ext, key);
            if (!v) return 0.0f;
            if (!v->is_number() || !(v->get<double>() >= 0.0 && v->get<double>() <= 1.0))
                throw Error(r.prefix() + key + " is not a number in [0, 1] (" + jsonValueText(*v) + ")");
            return float(v->get<double>());
        };
        m.clearcoat = factor("clearcoatFactor");
        m.clearcoatRoughness = factor("clearcoatRoughnessFactor");
        auto texture = [&](const char* key, ExtensionTexture& out) {
            const GltfValue* v = jsonMember(ext, key);
            if (!v) return;
            if (!v->is_object() || !jsonMember(v, "index"))
                r.fail(key, "expected a textureInfo object with an integer index, not " + jsonValueText(*v));
            out.info = v;
            out.index = int(r.integer(*jsonMember(v, "index"), std::string(key) + ".index", 0, std::numeric_limits<int>::max()));
            if (out.index >= int(model_.textures.size()))
                throw Error(r.prefix() + key + ".index " + std::to_string(out.index) + " names no texture");
            if (const GltfValue* t = jsonMember(v, "texCoord")) out.texCoord = int(r.integer(*t, std::string(key) + ".texCoord", 0, 1 << 16));
            if (const GltfValue* sv = jsonMember(v, "scale")) out.scale = float(r.number(*sv, std::string(key) + ".scale", -1e6, 1e6));
        };
        texture("clearcoatTexture", coat.factor);
        texture("clearcoatRoughnessTexture", coat.roughness);
        texture("clearcoatNormalTexture", coat.normal);
        return coat;
    }

    // Emitted radiance: emissiveFactor (glTF 3.9.2, linear, each in [0, 1]) times KHR_materials_emissive_strength's
    // emissiveStrength (>= 0, default 1). A factor or strength outside its range is an error naming the field.
    glm::vec3 emission(const tinygltf::Material& gm, const GltfValue* material, const GltfValueReader& reader) {
        glm::vec3 factor(0.0f);
        if (gm.emissiveFactor.size() == 3)
            for (int c = 0; c < 3; ++c) {
                double v = gm.emissiveFactor[size_t(c)];
                if (!(v >= -1e-3 && v <= 1.001))
                    reader.fail("emissiveFactor[" + std::to_string(c) + "]", std::to_string(v) + " is outside [0, 1]");
                factor[c] = std::clamp(float(v), 0.0f, 1.0f);
            }
        float strength = 1.0f;
        if (const GltfValue* ext = jsonMember(jsonMember(material, "extensions"), "KHR_materials_emissive_strength")) {
            if (!ext->is_object()) reader.fail("extensions.KHR_materials_emissive_strength", "expected an object, not " + jsonValueText(*ext));
            if (const GltfValue* v = jsonMember(ext, "emissiveStrength"))
                strength = float(reader.number(*v, "extensions.KHR_materials_emissive_strength.emissiveStrength", 0.0, 1e6));
        }
        return factor * strength;
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
        using GeometryKey = std::tuple<int, int, int, int, int, int>;  // POSITION, NORMAL, TANGENT, TEXCOORD_0, COLOR_0, indices
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
                GeometryKey key{attribute("POSITION"), attribute("NORMAL"), attribute("TANGENT"), attribute("TEXCOORD_0"),
                                attribute("COLOR_0"), primitive.indices};
                auto found = meshOfGeometry.find(key);
                uint32_t meshIndex;
                if (found != meshOfGeometry.end()) {
                    meshIndex = found->second;
                } else {
                    MeshData mesh = readPrimitive(primitive, model_.meshes[mi].name, int(mi));
                    if (mesh.indices.empty()) {
                        // Fewer than three indices: nothing to draw (and nothing a GPU upload may read past).
                        warnings_.add("mesh " + std::to_string(mi) + " has a primitive without a complete triangle; skipped");
                        meshOfGeometry[key] = kNoMesh;
                        continue;
                    }
                    meshIndex = uint32_t(scene_.meshes.size());
                    scene_.meshes.push_back(std::move(mesh));
                    meshOfGeometry[key] = meshIndex;
                }
                if (meshIndex == kNoMesh) continue;
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
        totalVertices_ += n;
        if (totalVertices_ > kMaxSceneVertices)
            throw Error(file_ + ": meshes: more than " + std::to_string(kMaxSceneVertices) + " vertices in total");
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
        readVertexColors(primitive, mesh, meshIndex);
        if (primitive.indices >= 0) {
            mesh.indices = readIndices(model_, primitive.indices, file_);
        } else {
            for (uint32_t i = 0; i < n; ++i) mesh.indices.push_back(i);
        }
        mesh.indices.resize(mesh.indices.size() / 3 * 3);
        mesh.indices.shrink_to_fit();
        totalIndices_ += mesh.indices.size();
        if (totalIndices_ > kMaxSceneIndices)
            throw Error(file_ + ": meshes: more than " + std::to_string(kMaxSceneIndices) + " indices in total");
        for (uint32_t index : mesh.indices)
            if (index >= n) throw Error(file_ + ": vertex index " + std::to_string(index) + " out of range in mesh " + std::to_string(meshIndex));
        for (const glm::vec3& p : mesh.positions) {
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw Error(file_ + ": non-finite vertex position in mesh " + std::to_string(meshIndex));
            if (glm::any(glm::greaterThan(glm::abs(p), glm::vec3(kMaxCoordinate))))
                throw Error(file_ + ": meshes[" + std::to_string(meshIndex) + "] POSITION " + std::to_string(p.x) + ", " +
                            std::to_string(p.y) + ", " + std::to_string(p.z) + " is beyond the coordinate limit " +
                            std::to_string(kMaxCoordinate));
        }
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
        // glTF's v runs down the image and its normal maps are +Y up: the bitangent points along -dP/dv.
        if (mesh.tangents.empty()) generateTangents(mesh, BitangentConvention::ImageUp);
        return mesh;
    }

    // COLOR_0 (glTF 3.7.2.1): VEC3 or VEC4, float or normalized unsigned byte / short, linear; it multiplies the
    // base colour (3.9.2). Non-finite or negative values are clamped to [0, 1] like the other colour inputs.
    void readVertexColors(const tinygltf::Primitive& primitive, MeshData& mesh, int meshIndex) {
        auto it = primitive.attributes.find("COLOR_0");
        if (it == primitive.attributes.end()) return;
        const tinygltf::Accessor& accessor = element(model_.accessors, it->second, "accessor", file_);
        const int components = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
        if (components != 3 && components != 4) {
            warnings_.add("COLOR_0 of mesh " + std::to_string(meshIndex) + " is not VEC3 or VEC4; ignored");
            return;
        }
        if (components == 4) {
            mesh.colors = readFloatAccessor<4>(model_, it->second, file_);
        } else {
            for (const glm::vec3& c : readFloatAccessor<3>(model_, it->second, file_)) mesh.colors.push_back(glm::vec4(c, 1.0f));
        }
        if (mesh.colors.size() != mesh.positions.size()) {
            warnings_.add("COLOR_0 of mesh " + std::to_string(meshIndex) + " has the wrong count; ignored");
            mesh.colors.clear();
            return;
        }
        for (glm::vec4& c : mesh.colors)
            for (int k = 0; k < 4; ++k) c[k] = std::isfinite(c[k]) ? std::clamp(c[k], 0.0f, 1.0f) : 1.0f;
    }

    void walkNodes() {
        areaLights_ = readAreaLights(json_, file_);   // GLIMMER_lights_area: bad values are one-line errors
        // The default scene (or scene 0); a file without scenes shows every mesh once at the origin.
        // Nodes may share children (a DAG is legal glTF), so the number of paths, not of nodes, bounds the work:
        // visits and instances are counted against kMaxInstances as they are made.
        std::vector<bool> onPath(model_.nodes.size(), false);
        uint64_t visits = 0, triangles = 0;
        std::function<void(int, const glm::mat4&, int)> visit = [&](int nodeIndex, const glm::mat4& parent, int depth) {
            const tinygltf::Node& node = element(model_.nodes, nodeIndex, "node", file_);
            if (onPath[size_t(nodeIndex)])
                throw Error(file_ + ": node hierarchy has a cycle at node " + std::to_string(nodeIndex));
            if (depth > kMaxHierarchyDepth)
                throw Error(file_ + ": node hierarchy is deeper than " + std::to_string(kMaxHierarchyDepth) + " at node " + std::to_string(nodeIndex));
            if (++visits > kMaxInstances)
                throw Error(file_ + ": nodes: the hierarchy expands to more than " + std::to_string(kMaxInstances) +
                            " node instances (nodes sharing children)");
            onPath[size_t(nodeIndex)] = true;
            glm::mat4 world = parent * nodeMatrix(node);
            if (node.mesh >= 0) {
                element(model_.meshes, node.mesh, "mesh", file_);
                if (!usableTransform(world, nodeIndex)) {
                    ++skippedInstances_;
                } else {
                    for (auto [meshIndex, material] : primitivesOfMesh_[size_t(node.mesh)]) {
                        triangles += scene_.meshes[meshIndex].indices.size() / 3;
                        if (scene_.instances.size() >= kMaxInstances || triangles > kMaxInstancedTriangles)
                            throw Error(file_ + ": nodes: instancing expands to more than " + std::to_string(kMaxInstances) +
                                        " instances or " + std::to_string(kMaxInstancedTriangles) + " triangles");
                        scene_.instances.push_back({meshIndex, material, world});
                    }
                }
            }
            if (node.camera >= 0) addCamera(element(model_.cameras, node.camera, "camera", file_), node, world);
            if (std::optional<int> light = nodeLight(jsonElement(rawNodes_, size_t(nodeIndex)), nodeIndex, file_)) {
                // Like a mesh: a zero-scale (or non-finite) node hides its light, with a warning naming the node.
                if (usableLightTransform(world)) {
                    gltfLights_.push_back(punctualLight(json_, *light, world, file_));
                } else {
                    punctualLight(json_, *light, glm::mat4(1.0f), file_);   // its own keys are still checked
                    warnings_.add("node " + std::to_string(nodeIndex) + " has a singular or non-finite transform (zero scale); its light is skipped");
                }
            }
            if (std::optional<int> light = nodeAreaLight(jsonElement(rawNodes_, size_t(nodeIndex)), nodeIndex, file_))
                gltfLights_.push_back(placeAreaLight(areaLights_, *light, world, file_));
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

    // A world transform that keeps the mesh finite, inside the coordinate limit and not flattened to nothing;
    // otherwise the instance is skipped with a warning naming the node (a zero scale hides a node on purpose).
    bool usableTransform(const glm::mat4& m, int nodeIndex) {
        std::string where = "node " + std::to_string(nodeIndex);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(m[c][r])) {
                    warnings_.add(where + " has a non-finite transform (matrix, translation, rotation or scale); its mesh is skipped");
                    return false;
                }
        if (glm::any(glm::greaterThan(glm::abs(glm::vec3(m[3])), glm::vec3(kMaxCoordinate)))) {
            warnings_.add(where + " translates beyond the coordinate limit; its mesh is skipped");
            return false;
        }
        float det = glm::determinant(glm::mat3(m));
        if (!(std::abs(det) > 1e-30f) || !std::isfinite(det)) {
            warnings_.add(where + " has a singular transform (zero scale or matrix); its mesh is skipped");
            return false;
        }
        return true;
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
        // glTF 3.10.2: yfov > 0 (radians), znear > 0; a field of view of pi or more shows nothing meaningful.
        std::string where = file_ + ": cameras[" + std::to_string(node.camera) + "].perspective.";
        if (!(gc.perspective.yfov > 0.0 && gc.perspective.yfov < 3.0))
            throw Error(where + "yfov " + std::to_string(gc.perspective.yfov) + " is outside (0, 3) radians");
        // znear within a scene file camera's range [1e-5, 1e3] m (scene_file.cpp readCamera); zfar, when given,
        // beyond it. A near plane past the whole model is refused once the bounds are known (addFramingCamera...).
        if (!(gc.perspective.znear >= kMinCameraNear && gc.perspective.znear <= kMaxCameraNear))
            throw Error(where + "znear " + std::to_string(gc.perspective.znear) + " is outside [1e-05, 1000]");
        if (gc.perspective.zfar != 0.0 && !(gc.perspective.zfar > gc.perspective.znear))
            throw Error(where + "zfar " + std::to_string(gc.perspective.zfar) + " is not beyond znear");
        glm::vec3 forwardAxis = glm::vec3(world * glm::vec4(0, 0, -1, 0)), upAxis = glm::vec3(world * glm::vec4(0, 1, 0, 0));
        bool finite = std::isfinite(glm::dot(forwardAxis, forwardAxis)) && std::isfinite(glm::dot(upAxis, upAxis)) &&
                      glm::all(glm::lessThanEqual(glm::abs(glm::vec3(world[3])), glm::vec3(kMaxCoordinate)));
        if (!finite || glm::length(forwardAxis) < 1e-12f || glm::length(glm::cross(forwardAxis, upAxis)) < 1e-12f)
            throw Error(file_ + ": the node of camera " + std::to_string(node.camera) +
                        " has a transform that is singular, non-finite or beyond the coordinate limit");
        camera.verticalFovDegrees = float(glm::degrees(gc.perspective.yfov));
        camera.nearPlane = float(gc.perspective.znear);
        gltfCameras_.push_back(camera);
        gltfCameraKeys_.push_back(where + "znear");
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
        for (size_t i = 0; i < gltfCameras_.size(); ++i) {
            Camera c = gltfCameras_[i];
            // Everything nearer than the near plane is clipped: a plane beyond the farthest corner of the model's
            // bounds would show the sky alone.
            float farthest = 0.0f;
            for (int corner = 0; corner < 8; ++corner)
                farthest = std::max(farthest, glm::distance(c.position, glm::vec3(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y,
                                                                                  corner & 4 ? hi.z : lo.z)));
            if (!(c.nearPlane < farthest))
                throw Error(gltfCameraKeys_[i] + " " + std::to_string(c.nearPlane) + " clips the whole model (its farthest point is " +
                            std::to_string(farthest) + " m from the camera)");
            std::string base = c.name;
            for (int k = 2; names.count(c.name); ++k) c.name = base + "_" + std::to_string(k);
            names.insert(c.name);
            scene_.cameras.push_back(c);
        }
        if (!gltfLights_.empty()) {
            scene_.lights = gltfLights_;   // the model's own KHR_lights_punctual lights
            return;
        }
        // Key light above and to the right; a weaker fill from just beside the default camera, so metals (which
        // have no diffuse term and, without an environment, no ambient) still show their highlights.
        scene_.fallbackLights = true;
        scene_.lights.push_back({LightType::Directional, glm::normalize(glm::vec3(0.5f, 0.8f, 0.6f)), glm::vec3(1.0f), 3.0f});
        glm::vec3 towardCamera = glm::normalize(camera.position - center);
        scene_.lights.push_back({LightType::Directional, glm::normalize(towardCamera + glm::vec3(-0.3f, 0.25f, 0.0f)),
                                 glm::vec3(1.0f), 1.0f});
    }

    const tinygltf::Model& model_;
    const GltfValue& json_;   // the same file's JSON, for what tinygltf reads lossily (scene/gltf_json.h)
    const GltfValue* rawNodes_ = jsonMember(&json_, "nodes");   // its "nodes" (looked up once: DAGs visit 2^20)
    std::string file_;
    Warnings warnings_;
    Scene scene_;
    std::map<std::tuple<int, bool, float, float, int>, int> textureCache_;
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> primitivesOfMesh_;
    std::vector<Camera> gltfCameras_;
    std::vector<std::string> gltfCameraKeys_;   // "<file>: cameras[i].perspective.znear" of each, for messages
    std::vector<Light> gltfLights_;
    std::vector<Light> areaLights_;   // GLIMMER_lights_area's list, placed by the nodes that refer to them
    std::vector<std::pair<std::string, std::string>> imageFileProblems_;
    int defaultMaterial_ = -1;
    uint64_t totalVertices_ = 0, totalIndices_ = 0, skippedInstances_ = 0;
    static constexpr uint32_t kNoMesh = 0xFFFFFFFFu;
};

// Decodes with tinygltf's own loader (stb_image), but only PNG and JPEG (the formats glTF 2.0 core allows,
// glTF 3.8.4), and only after the header's size was checked against the texture limits and the bytes that hold
// it: stb_image would otherwise allocate whatever a forged header claims. A format it cannot decode (KTX2,
// WebP of KHR_texture_basisu / EXT_texture_webp) becomes a warning: the image stays empty and textures using it
// are ignored, so the model still renders meaningfully.
bool checkedImageLoader(tinygltf::Image* image, const int index, std::string* error, std::string* warning, int width,
                        int height, const unsigned char* bytes, int size, void*) {
    auto ignore = [&](const std::string& why) {
        if (warning) *warning += "image " + std::to_string(index) + " " + why + "\n";
        image->width = image->height = 0;
        image->image.clear();
        return true;
    };
    std::string format = sniffImageFormat(bytes, size_t(std::max(size, 0)));
    if (format != "png" && format != "jpeg") return ignore("is not PNG or JPEG; textures using it are ignored");
    int w = 0, h = 0, channels = 0;
    if (!readImageHeader(bytes, size_t(size), w, h, channels)) return ignore("has an unreadable " + format + " header; ignored");
    try {
        checkImageSize("images[" + std::to_string(index) + "]", w, h, std::max(channels, 1), 1, uint64_t(size), ImageUse::Texture);
    } catch (const Error& e) {
        if (error) *error += std::string(e.what()) + "\n";
        return false;
    }
    std::string decodeError;
    if (tinygltf::LoadImageData(image, index, &decodeError, warning, width, height, bytes, size, nullptr)) return true;
    return ignore("could not be decoded (" + firstLine(decodeError) + ")");
}

// URI policy (README "Bad input"): external buffers and images must resolve, after percent-decoding (tinygltf)
// and following symlinks, to files inside the model's folder, unless --allow-outside-uris. A downloaded model
// must not read ~/.ssh/id_rsa through "../../.ssh/id_rsa". Files are read only when they are regular files (a FIFO
// would block) no larger than kMaxModelFileBytes. No "~" or "$VAR" expansion (tinygltf's default expands them).
struct FileAccess {
    std::filesystem::path root;  // canonical folder of the model
    bool allowOutside = false;
};
bool allowOutsideUris = false;

bool isInside(const std::filesystem::path& file, const std::filesystem::path& root) {
    auto f = file.begin(), r = root.begin();
    for (; r != root.end(); ++r, ++f)
        if (f == file.end() || *f != *r) return false;
    return f != file.end();
}

bool fsFileExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}

std::string fsExpandFilePath(const std::string& path, void*) { return path; }

bool fsReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    const FileAccess& access = *static_cast<const FileAccess*>(user);
    std::error_code ec;
    std::filesystem::path resolved = std::filesystem::weakly_canonical(path, ec);
    auto fail = [&](const std::string& why) {
        if (err) *err += why;
        return false;
    };
    if (ec) return fail("cannot resolve the path");
    if (!access.allowOutside && !isInside(resolved, access.root))
        return fail("refused: the URI leads outside the model's folder to " + resolved.string() + " (--allow-outside-uris permits it)");
    try {
        // The one reader of input files (core/files.h): a regular file within the model-file limit.
        readInputFile(resolved, kModelPartInput, *out);
    } catch (const Error& e) {
        std::string why = e.what();
        return fail(why.substr(std::min(why.size(), resolved.string().size() + 2)));   // the reason, without the path
    }
    return true;
}

bool fsWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "the loader never writes files";
    return false;
}

uint32_t littleEndian32(const unsigned char* p) { return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24; }

// Checks the first bytes of a model file: the GLB header, or that a .gltf starts with '{' (after a BOM and blanks).
void checkModelHeader(const std::vector<unsigned char>& bytes, const std::string& file, bool binary) {
    const size_t got = std::min<size_t>(bytes.size(), 12);
    const unsigned char* head = bytes.data();
    if (binary) {
        // GLB header (glTF 4.4.3): magic "glTF", version, total length.
        if (got < 12 || std::memcmp(head, "glTF", 4) != 0) throw Error(file + ": not a binary glTF (no 'glTF' magic)");
        uint32_t version = littleEndian32(head + 4), length = littleEndian32(head + 8);
        if (version != 2) throw Error(file + ": GLB header version " + std::to_string(version) + " (only 2 is supported)");
        if (length > bytes.size()) throw Error(file + ": GLB header length " + std::to_string(length) + " exceeds the file's " + std::to_string(bytes.size()) + " bytes");
    } else {
        size_t at = got >= 3 && head[0] == 0xEF && head[1] == 0xBB && head[2] == 0xBF ? 3 : 0;
        while (at < got && std::isspace(head[at])) ++at;
        if (got > 0 && at < got && head[at] != '{') throw Error(file + ": not a JSON glTF (does not start with '{')");
    }
}

}  // namespace

void setAllowOutsideUris(bool allow) { allowOutsideUris = allow; }

Scene loadGltfScene(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::error_code ec;
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    const bool binary = ext == ".glb";
    static_assert(kModelFileInput.maxBytes == kMaxModelFileBytes, "one model-file limit");
    std::vector<unsigned char> bytes;
    readInputFile(path, kModelFileInput, bytes);   // a regular file within the limit, else one line naming it
    checkModelHeader(bytes, file, binary);

    FileAccess access;
    access.root = std::filesystem::weakly_canonical(std::filesystem::absolute(path).parent_path(), ec);
    access.allowOutside = allowOutsideUris;
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(checkedImageLoader, nullptr);
    loader.SetFsCallbacks({fsFileExists, fsExpandFilePath, fsReadWholeFile, fsWriteWholeFile, &access});
    tinygltf::Model model;
    std::string error, warning;
    const std::string baseDir = std::filesystem::absolute(path).parent_path().string();
    bool ok = false;
    try {
        ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(), unsigned(bytes.size()), baseDir)
                    : loader.LoadASCIIFromString(&model, &error, &warning, reinterpret_cast<const char*>(bytes.data()),
                                                 unsigned(bytes.size()), baseDir);
    } catch (const std::exception& e) {
        throw Error(file + ": cannot load glTF (" + firstLine(e.what()) + ")");
    }
    if (!ok) {
        const std::string refused = refusedRequiredExtension(bytes, binary);
        if (!refused.empty())
            throw Error(file + ": requires extension " + refused + ", which Glimmer cannot read");
        throw Error(file + ": cannot load glTF (" + firstLine(error.empty() ? "unknown error" : error) + ")");
    }
    // What tinygltf reads lossily is read from the JSON itself, after a pre-scan (scene/gltf_json.h).
    const GltfValue json = parseGltfJson(bytes.data(), bytes.size(), binary, file);
    checkGltfJson(json, file);
    bytes = {};
    SceneBuilder builder(model, json, file);
    // tinygltf reports missing images and similar non-fatal problems as warnings, one per line. Its lines about
    // external image files ("File not found : X", "File read error : X : why", "Failed to load external 'uri' for
    // image[i] ...") become the reason in the builder's one warning per image, which names the file.
    std::vector<std::pair<std::string, std::string>> imageFileProblems;
    for (size_t start = 0; start < warning.size();) {
        size_t end = warning.find('\n', start);
        std::string line = firstLine(warning.substr(start, end == std::string::npos ? std::string::npos : end - start));
        const std::string notFound = "File not found : ", readError = "File read error : ";
        if (line.rfind(notFound, 0) == 0) {
            imageFileProblems.push_back({line.substr(notFound.size()), "was not found"});
        } else if (line.rfind(readError, 0) == 0) {
            std::string rest = line.substr(readError.size());
            size_t colon = rest.find(" : ");
            imageFileProblems.push_back({rest.substr(0, colon), "could not be read" + (colon == std::string::npos ? std::string() : " (" + rest.substr(colon + 3) + ")")});
        } else if (line.rfind("Failed to load external 'uri' for image[", 0) == 0 || line.rfind("Image data is empty for image[", 0) == 0) {
            // said by the builder's warning
        } else if (!line.empty()) {
            builder.warnings().add(line);
        }
        if (end == std::string::npos) break;
        start = end + 1;
    }
    builder.setImageFileProblems(std::move(imageFileProblems));
    try {
        return builder.build(path.stem().string());
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(file + ": invalid glTF (" + firstLine(e.what()) + ")");
    }
}

}  // namespace glimmer
