#include "scene/scene_file.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "core/error.h"
#include "core/files.h"
#include "core/image_io.h"
#include "core/log.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/mesh_builder.h"
#include "scene/scene_limits.h"
#include "scene/uv_transform.h"

namespace glimmer {
namespace {

using Json = nlohmann::json;

// Reads values out of the JSON with errors that name the file and the key path ("materials[2].alpha").
class Reader {
public:
    explicit Reader(std::filesystem::path file) : file_(std::move(file)) {}

    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw Error(file_.string() + ": " + where + ": " + what);
    }
    void checkKeys(const Json& object, const std::string& where, std::initializer_list<const char*> allowed) const {
        if (!object.is_object()) fail(where, "expected an object");
        for (const auto& item : object.items()) {
            bool known = false;
            for (const char* key : allowed) known |= item.key() == key;
            if (!known) {
                std::string list;
                for (const char* key : allowed) list += (list.empty() ? "" : ", ") + std::string(key);
                fail(where, "unknown key '" + item.key() + "' (known: " + list + ")");
            }
        }
    }
    float number(const Json& value, const std::string& where) const {
        if (!value.is_number()) fail(where, "expected a number");
        double v = value.get<double>();
        // The engine computes in float: 1e300 is finite as a double but infinite as a float.
        if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max()))
            fail(where, "expected a finite number (within float range)");
        return float(v);
    }
    float number(const Json& object, const char* key, const std::string& where, float fallback, float lo, float hi) const {
        if (!object.contains(key)) return fallback;
        float v = number(object[key], where + "." + key);
        if (v < lo || v > hi) fail(where + "." + key, "value " + std::to_string(v) + " outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return v;
    }
    int integer(const Json& object, const char* key, const std::string& where, int fallback, int lo, int hi) const {
        if (!object.contains(key)) return fallback;
        const Json& v = object[key];
        if (!v.is_number_integer()) fail(where + "." + key, "expected an integer");
        // Compare in 64 bits (unsigned JSON integers above 2^63 are out of range by definition): get<int>()
        // would wrap 4294967297 to 1.
        bool inRange = v.is_number_unsigned() ? v.get<uint64_t>() <= uint64_t(std::max(hi, 0)) && v.get<uint64_t>() >= uint64_t(std::max(lo, 0))
                                              : v.get<int64_t>() >= lo && v.get<int64_t>() <= hi;
        if (!inRange) fail(where + "." + key, "value " + v.dump() + " outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        return int(v.get<int64_t>());
    }
    bool boolean(const Json& object, const char* key, const std::string& where, bool fallback) const {
        if (!object.contains(key)) return fallback;
        if (!object[key].is_boolean()) fail(where + "." + key, "expected true or false");
        return object[key].get<bool>();
    }
    std::string string(const Json& object, const char* key, const std::string& where, const std::string& fallback = "") const {
        if (!object.contains(key)) return fallback;
        if (!object[key].is_string()) fail(where + "." + key, "expected a string");
        return object[key].get<std::string>();
    }
    template <int N>
    glm::vec<N, float> vec(const Json& value, const std::string& where) const {
        if (!value.is_array() || value.size() != size_t(N)) fail(where, "expected an array of " + std::to_string(N) + " numbers");
        glm::vec<N, float> v;
        for (int i = 0; i < N; ++i) v[i] = number(value[size_t(i)], where + "[" + std::to_string(i) + "]");
        return v;
    }
    // Colour: [r, g, b] or [r, g, b, a] (linear), each in [0, hi] (negative radiance or reflectance makes
    // physically meaningless images).
    glm::vec4 colour(const Json& value, const std::string& where, float hi = 1.0f) const {
        glm::vec4 c = value.is_array() && value.size() == 3 ? glm::vec4(vec<3>(value, where), 1.0f) : vec<4>(value, where);
        for (int i = 0; i < 4; ++i)
            if (!(c[i] >= 0.0f && c[i] <= hi))
                fail(where + "[" + std::to_string(i) + "]", "value " + std::to_string(c[i]) + " outside [0, " + std::to_string(hi) + "]");
        return c;
    }
    // A position in metres, each coordinate within kMaxCoordinate.
    glm::vec3 position(const Json& value, const std::string& where) const {
        glm::vec3 p = vec<3>(value, where);
        for (int i = 0; i < 3; ++i)
            if (std::abs(p[i]) > kMaxCoordinate)
                fail(where + "[" + std::to_string(i) + "]", "value " + std::to_string(p[i]) + " beyond the coordinate limit " + std::to_string(kMaxCoordinate));
        return p;
    }
    std::filesystem::path path(const Json& object, const char* key, const std::string& where) const {
        std::filesystem::path p = string(object, key, where);
        if (p.is_relative()) p = file_.parent_path() / p;
        return p;
    }
    const std::filesystem::path& file() const { return file_; }

private:
    std::filesystem::path file_;
};

// Transform from "translation" [x,y,z], "rotationDegrees" [x,y,z] (applied about x, then y, then z) and
// "scale" (number or [x,y,z]): M = T * Rz * Ry * Rx * S.
glm::mat4 readTransform(const Reader& r, const Json& o, const std::string& where) {
    glm::mat4 m(1.0f);
    if (o.contains("translation")) m = glm::translate(m, r.position(o["translation"], where + ".translation"));
    if (o.contains("rotationDegrees")) {
        glm::vec3 deg = r.vec<3>(o["rotationDegrees"], where + ".rotationDegrees");
        m = glm::rotate(m, glm::radians(deg.z), glm::vec3(0, 0, 1));
        m = glm::rotate(m, glm::radians(deg.y), glm::vec3(0, 1, 0));
        m = glm::rotate(m, glm::radians(deg.x), glm::vec3(1, 0, 0));
    }
    if (o.contains("scale")) {
        glm::vec3 s = o["scale"].is_number() ? glm::vec3(r.number(o["scale"], where + ".scale")) : r.vec<3>(o["scale"], where + ".scale");
        for (int i = 0; i < 3; ++i)
            if (!(std::abs(s[i]) >= 1e-6f && std::abs(s[i]) <= 1e6f))
                r.fail(where + ".scale", "each scale must have a magnitude in [1e-6, 1e6]");
        m = glm::scale(m, s);
    }
    return m;
}

MeshData generatedMesh(const Reader& r, const Json& o, const std::string& where) {
    r.checkKeys(o, where, {"name", "generator", "halfExtent", "cells", "uvOffset", "radius", "segments", "rings", "size", "height"});
    std::string generator = r.string(o, "generator", where);
    MeshData mesh;
    if (generator == "plane") {
        mesh = makeGroundPlane(r.number(o, "halfExtent", where, 1.0f, 1e-4f, 1e5f), r.integer(o, "cells", where, 1, 1, 2048),
                               r.number(o, "uvOffset", where, 0.0f, -1e6f, 1e6f));
    } else if (generator == "heightmap") {
        mesh = makeHeightmapPlane(r.number(o, "halfExtent", where, 4.0f, 1e-4f, 1e5f), r.integer(o, "cells", where, 256, 1, 2048),
                                  r.number(o, "uvOffset", where, 0.0f, -1e6f, 1e6f));
    } else if (generator == "sphere") {
        mesh = makeUvSphere(r.number(o, "radius", where, 1.0f, 1e-4f, 1e5f), r.integer(o, "segments", where, 64, 3, 4096),
                            r.integer(o, "rings", where, 32, 2, 4096));
    } else if (generator == "box") {
        glm::vec3 size = o.contains("size") ? r.vec<3>(o["size"], where + ".size") : glm::vec3(1.0f);
        if (glm::any(glm::lessThanEqual(size, glm::vec3(0.0f)))) r.fail(where + ".size", "sizes must be positive");
        MeshBuilder b("box");
        b.box(glm::vec3(-0.5f * size.x, 0.0f, -0.5f * size.z), glm::vec3(0.5f * size.x, size.y, 0.5f * size.z), glm::vec3(0.0f));
        mesh = b.finish();
    } else if (generator == "cylinder") {
        MeshBuilder b("cylinder");
        b.cylinder(glm::vec3(0.0f), r.number(o, "radius", where, 0.5f, 1e-4f, 1e5f), r.number(o, "height", where, 1.0f, 1e-4f, 1e5f),
                   r.integer(o, "segments", where, 32, 3, 4096));
        mesh = b.finish();
    } else {
        r.fail(where + ".generator", "unknown generator '" + generator + "' (known: plane, heightmap, sphere, box, cylinder)");
    }
    mesh.name = r.string(o, "name", where, generator);
    return mesh;
}

int loadTexture(Scene& scene, const Reader& r, const Json& o, const char* key, const std::string& where, bool srgb) {
    if (!o.contains(key)) return -1;
    std::filesystem::path path = r.path(o, key, where);
    ImageF image;
    try {
        image = readImage(path, ImageUse::Texture);
    } catch (const Error& e) {
        r.fail(where + "." + key, e.what());
    }
    TextureData t;
    t.name = path.filename().string();
    t.width = image.width;
    t.height = image.height;
    t.srgb = srgb;
    t.rgba.resize(size_t(image.width) * image.height * 4);
    // Grey maps to RGB and grey+alpha to RGB+A; values stay as stored (sRGB-encoded for colour images).
    const int n = image.channels;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            float grey = image.at(x, y, 0);
            float v[4] = {grey, grey, grey, 1.0f};
            if (n >= 3) for (int c = 0; c < 3; ++c) v[c] = image.at(x, y, c);
            if (n == 2 || n >= 4) v[3] = image.at(x, y, n == 2 ? 1 : 3);
            for (int c = 0; c < 4; ++c)
                t.rgba[(size_t(y) * image.width + x) * 4 + c] = uint8_t(std::lround(std::clamp(v[c], 0.0f, 1.0f) * 255.0f));
        }
    scene.textures.push_back(std::move(t));
    return int(scene.textures.size() - 1);
}

// Fills or overrides the fields present in `o` (materials of the base scene keep what the file leaves out).
void readMaterial(Scene& scene, const Reader& r, const Json& o, const std::string& where, Material& m) {
    r.checkKeys(o, where, {"name", "baseColor", "alpha", "roughness", "metallic", "ndf", "glinty", "glintDensityScale",
                           "alphaCutoff", "doubleSided", "baseColorTexture", "metallicRoughnessTexture", "normalTexture",
                           "occlusionTexture", "glintMaskTexture", "uvScale", "uvOffset", "uvRotationDegrees", "glint",
                           "clearcoat", "clearcoatRoughness", "clearcoatTexture", "clearcoatRoughnessTexture",
                           "clearcoatNormalTexture", "emissive"});
    if (o.contains("baseColor")) m.baseColor = r.colour(o["baseColor"], where + ".baseColor");
    // Emitted radiance (linear RGB, the renderer's radiance units): the visible face of an area light, for example.
    if (o.contains("emissive")) m.emissive = glm::vec3(r.colour(o["emissive"], where + ".emissive", 1e6f));
    if (o.contains("alpha") && o.contains("roughness")) r.fail(where, "give either alpha or roughness, not both");
    m.alpha = r.number(o, "alpha", where, m.alpha, 1e-3f, 1.0f);
    if (o.contains("roughness")) {
        float roughness = r.number(o, "roughness", where, 0.5f, 0.0f, 1.0f);
        m.alpha = std::max(roughness * roughness, 1e-3f);
    }
    m.metallic = r.number(o, "metallic", where, m.metallic, 0.0f, 1.0f);
    if (o.contains("ndf")) {
        std::string ndf = r.string(o, "ndf", where);
        if (ndf == "ggx") m.ndf = NdfType::Ggx;
        else if (ndf == "beckmann") m.ndf = NdfType::Beckmann;
        else r.fail(where + ".ndf", "expected \"ggx\" or \"beckmann\"");
    }
    m.glinty = r.boolean(o, "glinty", where, m.glinty);
    m.glintDensityScale = r.number(o, "glintDensityScale", where, m.glintDensityScale, 0.0f, 1e6f);
    if (o.contains("glint")) {
        // The glint material, same keys and ranges as the glTF extension GLIMMER_materials_glint (its
        // densityTexture is this file's glintMaskTexture); giving it makes the material glinty.
        const Json& g = o["glint"];
        std::string gw = where + ".glint";
        if (!g.is_object()) r.fail(gw, "expected an object");
        r.checkKeys(g, gw, {"density", "angularSize", "color", "colorVariation", "anisotropy"});
        m.glint.density = r.number(g, "density", gw, m.glint.density, 0.0f, 1e14f);
        m.glint.angularSize = r.number(g, "angularSize", gw, m.glint.angularSize, 0.0005f, 0.5f);
        if (g.contains("color")) m.glint.color = glm::vec3(r.colour(g["color"], gw + ".color"));
        m.glint.colorVariation = r.number(g, "colorVariation", gw, m.glint.colorVariation, 0.0f, 1.0f);
        m.glint.anisotropy = r.number(g, "anisotropy", gw, m.glint.anisotropy, 1.0f, 64.0f);
        m.glinty = r.boolean(o, "glinty", where, true);
    }
    // KHR_materials_clearcoat's factors (same names and ranges as clearcoatFactor, clearcoatRoughnessFactor).
    m.clearcoat = r.number(o, "clearcoat", where, m.clearcoat, 0.0f, 1.0f);
    m.clearcoatRoughness = r.number(o, "clearcoatRoughness", where, m.clearcoatRoughness, 0.0f, 1.0f);
    m.alphaCutoff = r.number(o, "alphaCutoff", where, m.alphaCutoff, -1.0f, 1.0f);
    m.doubleSided = r.boolean(o, "doubleSided", where, m.doubleSided);
    if (int t = loadTexture(scene, r, o, "baseColorTexture", where, true); t >= 0) m.baseColorTexture = t;
    if (int t = loadTexture(scene, r, o, "metallicRoughnessTexture", where, false); t >= 0) m.metallicRoughnessTexture = t;
    if (int t = loadTexture(scene, r, o, "normalTexture", where, false); t >= 0) m.normalTexture = t;
    if (int t = loadTexture(scene, r, o, "occlusionTexture", where, false); t >= 0) m.occlusionTexture = t;
    if (int t = loadTexture(scene, r, o, "glintMaskTexture", where, false); t >= 0) m.glintMaskTexture = t;
    if (int t = loadTexture(scene, r, o, "clearcoatTexture", where, false); t >= 0) m.clearcoatTexture = t;
    if (int t = loadTexture(scene, r, o, "clearcoatRoughnessTexture", where, false); t >= 0) m.clearcoatRoughnessTexture = t;
    if (int t = loadTexture(scene, r, o, "clearcoatNormalTexture", where, false); t >= 0) m.clearcoatNormalTexture = t;
    if (o.contains("uvScale") || o.contains("uvOffset") || o.contains("uvRotationDegrees")) {
        // Same convention as KHR_texture_transform: uv' = T * R * S * uv.
        glm::vec2 scale = !o.contains("uvScale") ? glm::vec2(1.0f)
                          : o["uvScale"].is_number() ? glm::vec2(r.number(o["uvScale"], where + ".uvScale"))
                                                     : r.vec<2>(o["uvScale"], where + ".uvScale");
        glm::vec2 offset = o.contains("uvOffset") ? r.vec<2>(o["uvOffset"], where + ".uvOffset") : glm::vec2(0.0f);
        float rotation = glm::radians(r.number(o, "uvRotationDegrees", where, 0.0f, -3600.0f, 3600.0f));
        m.uvTransform = uvTransformMatrix(offset, rotation, scale);
    }
}

// A unit direction, not zero, from `key`.
glm::vec3 readDirection(const Reader& r, const Json& o, const char* key, const std::string& where) {
    glm::vec3 d = r.vec<3>(o[key], where + "." + key);
    if (glm::length(d) < 1e-6f) r.fail(where + "." + key, "must not be zero");
    return glm::normalize(d);
}

Light readLight(const Reader& r, const Json& o, const std::string& where) {
    r.checkKeys(o, where, {"type", "direction", "position", "color", "intensity", "range", "innerConeAngle",
                           "outerConeAngle", "angularDiameterDegrees", "radius", "right", "width", "height",
                           "twoSided"});
    Light light;
    std::string type = r.string(o, "type", where, "directional");
    // Keys that only some types take: a one-line error instead of a silently ignored value.
    auto only = [&](const char* key, std::initializer_list<const char*> types) {
        if (!o.contains(key)) return;
        for (const char* t : types)
            if (type == t) return;
        std::string list;
        for (const char* t : types) list += (list.empty() ? "" : ", ") + std::string(t);
        r.fail(where + "." + key, "does not apply to a " + type + " light (only " + list + ")");
    };
    only("angularDiameterDegrees", {"directional"});
    only("radius", {"point", "spot", "disk", "sphere"});
    only("right", {"rect", "disk"});
    only("width", {"rect"});
    only("height", {"rect"});
    only("twoSided", {"rect", "disk"});
    only("innerConeAngle", {"spot"});
    only("outerConeAngle", {"spot"});
    if (type == "directional") {
        light.type = LightType::Directional;
        if (!o.contains("direction")) r.fail(where, "a directional light needs \"direction\" (towards the light)");
        light.vector = readDirection(r, o, "direction", where);
        // The sun's disk: its solid angle is what the glints of Kneiphof & Klein 2024 count against.
        light.angularDiameter = glm::radians(r.number(o, "angularDiameterDegrees", where, 0.53f, 0.0f, 90.0f));
    } else if (type == "point") {
        light.type = LightType::Point;
        if (!o.contains("position")) r.fail(where, "a point light needs \"position\"");
        light.vector = r.position(o["position"], where + ".position");
        light.radius = r.number(o, "radius", where, 0.0f, 0.0f, 1e3f);
    } else if (type == "spot") {
        // KHR_lights_punctual's spot: cone angles in radians about `direction` (the way the light shines).
        light.type = LightType::Spot;
        if (!o.contains("position") || !o.contains("direction"))
            r.fail(where, "a spot light needs \"position\" and \"direction\" (the way it shines)");
        light.vector = r.position(o["position"], where + ".position");
        light.spotDirection = readDirection(r, o, "direction", where);
        light.outerConeAngle = r.number(o, "outerConeAngle", where, light.outerConeAngle, 1e-4f, 1.5707964f);
        light.innerConeAngle = r.number(o, "innerConeAngle", where, 0.0f, 0.0f, 1.5707964f);
        if (!(light.innerConeAngle < light.outerConeAngle))
            r.fail(where + ".innerConeAngle", "must be smaller than outerConeAngle");
        light.radius = r.number(o, "radius", where, 0.0f, 0.0f, 1e3f);
    } else if (type == "rect" || type == "disk" || type == "sphere") {
        // Area lights (docs/area_lights.md): a centre, a size in metres; rects and disks face `direction` (the way
        // they shine), with the width along `right`.
        light.type = type == "rect" ? LightType::Rect : type == "disk" ? LightType::Disk : LightType::Sphere;
        if (!o.contains("position")) r.fail(where, "a " + type + " light needs \"position\" (its centre)");
        light.vector = r.position(o["position"], where + ".position");
        if (type != "sphere") {
            if (!o.contains("direction")) r.fail(where, "a " + type + " light needs \"direction\" (the way it shines)");
            light.spotDirection = readDirection(r, o, "direction", where);
            glm::vec3 right = o.contains("right") ? readDirection(r, o, "right", where)
                              : std::abs(light.spotDirection.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f)
                                                                        : glm::vec3(1.0f, 0.0f, 0.0f);
            if (!o.contains("right")) right = glm::cross(right, light.spotDirection);   // horizontal when possible
            right -= light.spotDirection * glm::dot(light.spotDirection, right);
            if (glm::length(right) < 1e-3f) r.fail(where + ".right", "must not be parallel to direction");
            light.right = glm::normalize(right);
            light.twoSided = r.boolean(o, "twoSided", where, false);
        }
        if (type == "rect") {
            if (!o.contains("width") || !o.contains("height")) r.fail(where, "a rect light needs \"width\" and \"height\" (metres)");
            light.width = r.number(o, "width", where, 1.0f, 1e-4f, 1e4f);
            light.height = r.number(o, "height", where, 1.0f, 1e-4f, 1e4f);
        } else {
            if (!o.contains("radius")) r.fail(where, "a " + type + " light needs \"radius\" (metres)");
            light.radius = r.number(o, "radius", where, 1.0f, 1e-4f, 1e4f);
        }
    } else {
        r.fail(where + ".type", "expected \"directional\", \"point\", \"spot\", \"rect\", \"disk\" or \"sphere\"");
    }
    if (type != "directional") light.range = r.number(o, "range", where, 0.0f, 0.0f, 1e7f);
    if (o.contains("color")) light.color = glm::vec3(r.colour(o["color"], where + ".color", 1e6f));
    light.intensity = r.number(o, "intensity", where, 1.0f, 0.0f, 1e9f);
    return light;
}

Camera readCamera(const Reader& r, const Json& o, const std::string& where) {
    r.checkKeys(o, where, {"name", "position", "target", "up", "fov", "near"});
    Camera c;
    c.name = r.string(o, "name", where);
    if (c.name.empty()) r.fail(where + ".name", "every camera needs a name");
    if (!o.contains("position") || !o.contains("target")) r.fail(where, "a camera needs \"position\" and \"target\"");
    c.position = r.position(o["position"], where + ".position");
    c.target = r.position(o["target"], where + ".target");
    if (o.contains("up")) c.up = r.vec<3>(o["up"], where + ".up");
    if (glm::length(c.target - c.position) < 1e-6f) r.fail(where, "position and target coincide");
    if (glm::length(glm::cross(c.target - c.position, c.up)) < 1e-6f) r.fail(where + ".up", "parallel to the view direction");
    c.verticalFovDegrees = r.number(o, "fov", where, c.verticalFovDegrees, 1.0f, 170.0f);
    c.nearPlane = r.number(o, "near", where, c.nearPlane, kMinCameraNear, kMaxCameraNear);
    return c;
}

// Appends a glTF file's meshes, materials, textures and instances (under `transform`) to the scene.
void mergeModel(Scene& scene, const Reader& r, const Json& o, const std::string& where, std::vector<Light>& modelLights) {
    r.checkKeys(o, where, {"gltf", "translation", "rotationDegrees", "scale", "glinty", "glintDensityScale"});
    if (!o.contains("gltf")) r.fail(where, "a model needs \"gltf\" (a path relative to the scene file)");
    std::filesystem::path path = r.path(o, "gltf", where);
    Scene model;
    try {
        model = loadGltfScene(path);
    } catch (const Error& e) {
        r.fail(where + ".gltf", e.what());
    }
    glm::mat4 transform = readTransform(r, o, where);
    uint32_t meshBase = uint32_t(scene.meshes.size()), materialBase = uint32_t(scene.materials.size());
    int textureBase = int(scene.textures.size());
    for (MeshData& mesh : model.meshes) scene.meshes.push_back(std::move(mesh));
    for (TextureData& texture : model.textures) scene.textures.push_back(std::move(texture));
    for (Material m : model.materials) {
        for (int* t : materialTextureSlots(m))
            if (*t >= 0) *t += textureBase;
        m.glinty = r.boolean(o, "glinty", where, m.glinty);
        m.glintDensityScale = r.number(o, "glintDensityScale", where, m.glintDensityScale, 0.0f, 1e6f);
        scene.materials.push_back(m);
    }
    for (const Instance& instance : model.instances)
        scene.instances.push_back({instance.mesh + meshBase, instance.material + materialBase, transform * instance.transform});
    // Glint densities are per square metre: a scaled model has more surface per unit UV area.
    float areaScale = std::pow(std::abs(glm::determinant(glm::mat3(transform))), 2.0f / 3.0f);
    for (size_t i = materialBase; i < scene.materials.size(); ++i) scene.materials[i].surfacePerUvArea *= areaScale;
    // The model's cameras (its framing camera, named after the file, and its own) and its KHR_lights_punctual
    // lights come along under the model's transform; a `cameras` key replaces them, `lights` adds to them.
    std::unordered_set<std::string> cameraNames;
    for (const Camera& c : scene.cameras) cameraNames.insert(c.name);
    for (Camera c : model.cameras) {
        if (c.name == "default") c.name = path.stem().string();
        std::string base = c.name;
        for (int k = 2; cameraNames.count(c.name); ++k) c.name = base + "_" + std::to_string(k);
        cameraNames.insert(c.name);
        c.position = glm::vec3(transform * glm::vec4(c.position, 1.0f));
        c.target = glm::vec3(transform * glm::vec4(c.target, 1.0f));
        c.up = glm::normalize(glm::vec3(transform * glm::vec4(c.up, 0.0f)));
        scene.cameras.push_back(c);
    }
    if (!model.fallbackLights)
        for (Light light : model.lights) {
            if (light.type == LightType::Directional) {
                light.vector = glm::normalize(glm::vec3(transform * glm::vec4(light.vector, 0.0f)));
            } else {
                light.vector = glm::vec3(transform * glm::vec4(light.vector, 1.0f));
                light.spotDirection = glm::normalize(glm::vec3(transform * glm::vec4(light.spotDirection, 0.0f)));
                glm::vec3 right = glm::vec3(transform * glm::vec4(light.right, 0.0f));
                right -= light.spotDirection * glm::dot(light.spotDirection, right);
                if (glm::length(right) > 1e-6f) light.right = glm::normalize(right);
            }
            scene.lights.push_back(light);
            modelLights.push_back(light);
        }
}

// Names to indices; a name given twice resolves to its last entry (a scene file's material overrides a model's).
using NameIndex = std::unordered_map<std::string, uint32_t>;
template <class T>
NameIndex indexByName(const std::vector<T>& items) {
    NameIndex index;
    index.reserve(items.size());
    for (size_t i = 0; i < items.size(); ++i) index[items[i].name] = uint32_t(i);
    return index;
}

uint32_t findByName(const Reader& r, const NameIndex& names, const Json& o, const char* key, const std::string& where) {
    std::string name = r.string(o, key, where);
    if (auto it = names.find(name); it != names.end()) return it->second;
    // Name a few of the known ones (sorted), not all: a scene may have 100k materials.
    std::vector<std::string> known;
    for (const auto& entry : names) known.push_back(entry.first);
    std::sort(known.begin(), known.end());
    std::string list;
    for (size_t i = 0; i < known.size() && i < 20; ++i) list += (list.empty() ? "" : ", ") + known[i];
    if (known.size() > 20) list += ", ... (" + std::to_string(known.size()) + " in all)";
    r.fail(where + "." + key, "no " + std::string(key) + " named '" + name.substr(0, 200) + "' (have: " + list + ")");
}

// User glint methods the scene comes with (glints/user/user_methods.h), relative to the scene file; loaded by the
// command line (readSceneMethodFiles) before the scene itself, so --method and --set can name them.
std::vector<std::string> methodFilesOf(const Reader& r, const Json& doc, const std::filesystem::path& path) {
    std::vector<std::string> files;
    if (!doc.is_object() || !doc.contains("methodFiles")) return files;
    const Json& list = doc["methodFiles"];
    if (!list.is_array()) r.fail("methodFiles", "expected an array");
    for (size_t i = 0; i < list.size(); ++i) {
        if (!list[i].is_string() || list[i].get<std::string>().empty())
            r.fail("methodFiles[" + std::to_string(i) + "]", "expected the path of a .glsl method file");
        std::filesystem::path p = list[i].get<std::string>();
        files.push_back((p.is_relative() ? path.parent_path() / p : p).string());
    }
    return files;
}

// nlohmann's DOM parser, remembering the last key read so that a syntax error can name its field. (A parse
// callback did this before, but nlohmann's callback parser rescans the enclosing array at the end of every
// object: 100k materials took 7 s.)
struct KeyTrackingParser {
    explicit KeyTrackingParser(Json& doc) : dom(doc, true) {}
    nlohmann::detail::json_sax_dom_parser<Json> dom;
    std::string lastKey;

    bool null() { return dom.null(); }
    bool boolean(bool v) { return dom.boolean(v); }
    bool number_integer(Json::number_integer_t v) { return dom.number_integer(v); }
    bool number_unsigned(Json::number_unsigned_t v) { return dom.number_unsigned(v); }
    bool number_float(Json::number_float_t v, const std::string& s) { return dom.number_float(v, s); }
    bool string(std::string& v) { return dom.string(v); }
    bool binary(Json::binary_t& v) { return dom.binary(v); }
    bool start_object(std::size_t n) { return dom.start_object(n); }
    bool key(std::string& k) {
        lastKey = k.substr(0, 200);
        return dom.key(k);
    }
    bool end_object() { return dom.end_object(); }
    bool start_array(std::size_t n) { return dom.start_array(n); }
    bool end_array() { return dom.end_array(); }
    template <class Exception>
    bool parse_error(std::size_t position, const std::string& token, const Exception& ex) { return dom.parse_error(position, token, ex); }
};

}  // namespace

std::vector<std::string> readSceneMethodFiles(const std::filesystem::path& path) {
    std::string text;
    try {
        text = readInputFile(path, kSceneFileInput);
    } catch (const Error&) {
        return {};   // loadSceneFile reports it
    }
    Json doc = Json::parse(text, nullptr, false);
    if (doc.is_discarded()) return {};   // loadSceneFile reports the syntax error with its position
    return methodFilesOf(Reader(path), doc, path);
}

Scene loadSceneFile(const std::filesystem::path& path) {
    // readInputFile: a regular file within kSceneFileInput's limit, else one line naming the path.
    static_assert(kSceneFileInput.maxBytes == kMaxSceneFileBytes, "one scene-file limit");
    const std::string text = readInputFile(path, kSceneFileInput);
    Reader r(path);
    Json doc;
    KeyTrackingParser parser(doc);
    try {
        Json::sax_parse(text, &parser);
    } catch (const Json::exception& e) {
        // parse_error, and out_of_range for numbers such as 1e309 that overflow a double.
        std::string what = e.what();
        const std::string& lastKey = parser.lastKey;
        throw Error(path.string() + ": invalid JSON" + (lastKey.empty() ? "" : " at key '" + lastKey + "'") + " (" +
                    what.substr(what.find(']') == std::string::npos ? 0 : what.find(']') + 2) + ")");
    }
    r.checkKeys(doc, "scene", {"name", "base", "sky", "environment", "meshes", "models", "materials", "instances",
                               "lights", "cameras", "walkthrough", "description", "methodFiles"});

    Scene scene;
    if (doc.contains("base")) {
        std::string base = r.string(doc, "base", "scene");
        if (!isBuiltinScene(base)) {
            std::string known;
            for (const std::string& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
            r.fail("base", "unknown generated scene '" + base + "' (known: " + known + ")");
        }
        scene = makeBuiltinScene(base);
    }
    scene.name = r.string(doc, "name", "scene", path.stem().string());
    if (doc.contains("sky")) scene.skyColor = glm::vec3(r.colour(doc["sky"], "sky", 1e6f));
    if (doc.contains("environment")) {
        std::string env = r.string(doc, "environment", "scene");
        scene.environment = env.empty() || env == "none" ? env : r.path(doc, "environment", "scene").string();
    }

    auto array = [&](const char* key) -> const Json& {
        static const Json empty = Json::array();
        if (!doc.contains(key)) return empty;
        if (!doc[key].is_array()) r.fail(key, "expected an array");
        return doc[key];
    };
    auto at = [](const char* key, size_t i) { return std::string(key) + "[" + std::to_string(i) + "]"; };

    scene.methodFiles = methodFilesOf(r, doc, path);

    const Json& models = array("models");
    std::vector<Light> modelLights;
    for (size_t i = 0; i < models.size(); ++i) mergeModel(scene, r, models[i], at("models", i), modelLights);
    const Json& meshes = array("meshes");
    for (size_t i = 0; i < meshes.size(); ++i) scene.meshes.push_back(generatedMesh(r, meshes[i], at("meshes", i)));

    const Json& materials = array("materials");
    // A material named like an existing one overrides the first of that name (a model's), as before the index.
    std::unordered_map<std::string, size_t> firstMaterial;
    for (size_t i = scene.materials.size(); i-- > 0;) firstMaterial[scene.materials[i].name] = i;
    for (size_t i = 0; i < materials.size(); ++i) {
        std::string where = at("materials", i);
        std::string name = r.string(materials[i], "name", where);
        if (name.empty()) r.fail(where + ".name", "every material needs a name");
        if (auto existing = firstMaterial.find(name); existing == firstMaterial.end()) {
            Material m;
            m.name = name;
            readMaterial(scene, r, materials[i], where, m);
            firstMaterial[name] = scene.materials.size();
            scene.materials.push_back(m);
        } else {
            readMaterial(scene, r, materials[i], where, scene.materials[existing->second]);
        }
    }

    const NameIndex meshNames = indexByName(scene.meshes), materialNames = indexByName(scene.materials);
    const Json& instances = array("instances");
    for (size_t i = 0; i < instances.size(); ++i) {
        std::string where = at("instances", i);
        r.checkKeys(instances[i], where, {"mesh", "material", "translation", "rotationDegrees", "scale"});
        Instance instance;
        instance.mesh = findByName(r, meshNames, instances[i], "mesh", where);
        instance.material = findByName(r, materialNames, instances[i], "material", where);
        instance.transform = readTransform(r, instances[i], where);
        scene.instances.push_back(instance);
    }

    if (doc.contains("lights")) {
        scene.lights.clear();   // replaces the base scene's lights; the models' own lights stay
        const Json& lights = array("lights");
        for (size_t i = 0; i < lights.size(); ++i) scene.lights.push_back(readLight(r, lights[i], at("lights", i)));
        scene.lights.insert(scene.lights.end(), modelLights.begin(), modelLights.end());
    }
    if (scene.lights.empty()) {
        log::info(path.string(), ": no lights in the scene file or its models; lit by a default sun");
        scene.lights.push_back({LightType::Directional, glm::normalize(glm::vec3(0.5f, 0.8f, 0.6f)), glm::vec3(1.0f), 3.0f});
        scene.fallbackLights = true;
    }
    if (doc.contains("cameras")) {
        scene.cameras.clear();
        const Json& cameras = array("cameras");
        std::unordered_set<std::string> names;
        for (size_t i = 0; i < cameras.size(); ++i) {
            Camera c = readCamera(r, cameras[i], at("cameras", i));
            if (!names.insert(c.name).second) r.fail(at("cameras", i) + ".name", "duplicate camera name '" + c.name + "'");
            scene.cameras.push_back(c);
        }
    }
    if (doc.contains("walkthrough")) {
        const Json& order = array("walkthrough");
        scene.walkthrough.clear();
        const NameIndex cameraNames = indexByName(scene.cameras);
        for (size_t i = 0; i < order.size(); ++i) {
            if (!order[i].is_string()) r.fail(at("walkthrough", i), "expected a camera name");
            std::string name = order[i].get<std::string>();
            if (!cameraNames.count(name)) r.fail(at("walkthrough", i), "no camera named '" + name.substr(0, 200) + "'");
            scene.walkthrough.push_back(name);
        }
    }

    if (scene.instances.empty()) throw Error(path.string() + ": scene has nothing to render (no base, models or instances)");
    if (scene.cameras.empty()) throw Error(path.string() + ": scene has no camera");
    return scene;
}

}  // namespace glimmer
