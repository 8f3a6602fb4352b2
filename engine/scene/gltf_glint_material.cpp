#include "scene/gltf_glint_material.h"

#include <cmath>
#include <limits>
#include <map>

#include "core/error.h"

namespace glimmer {

const std::vector<GlintKey>& glintKeys() {
    static const std::vector<GlintKey> keys = {
        {"density", "number", 0.0, 1e14, "glint facets per square metre of surface"},
        {"angularSize", "number", 0.0005, 0.5,
         "half-angle in radians of the cone around the half vector in which one facet reflects"},
        {"color", "color", 0.0, 1.0, "linear RGB tint of the glints"},
        {"colorVariation", "number", 0.0, 1.0, "0: every glint has `color`; 1: random hues around it"},
        {"anisotropy", "number", 1.0, 64.0, "stretch of each glint along the tangent"},
        {"densityTexture", "textureInfo", 0.0, 0.0, "red channel multiplies the density (TEXCOORD_0)"},
    };
    return keys;
}

namespace {

// "0.5", "-1", "4294967296" for messages: the value as the file wrote it.
std::string valueText(const GltfValue& v) { return jsonValueText(v); }

// Applies one key's value; returns an error text ("" when accepted). Values come from the file's JSON
// (scene/gltf_json.h), so integers of any width are read as the numbers they are, and null is a wrong type.
std::string applyKey(const GlintKey& key, const GltfValue& v, Material& m, const std::function<int(int)>& texture) {
    const std::string type = key.type;
    if (type == "number") {
        if (!v.is_number()) return "expected a number, not " + valueText(v);
        double x = v.get<double>();
        if (!(x >= key.minValue && x <= key.maxValue))
            return "value " + valueText(v) + " outside [" + std::to_string(key.minValue) + ", " +
                   std::to_string(key.maxValue) + "]";
        std::string name = key.name;
        if (name == "density") m.glint.density = float(x);
        else if (name == "angularSize") m.glint.angularSize = float(x);
        else if (name == "colorVariation") m.glint.colorVariation = float(x);
        else if (name == "anisotropy") m.glint.anisotropy = float(x);
        return "";
    }
    if (type == "color") {
        if (!v.is_array() || v.size() != 3) return "expected [r, g, b], not " + valueText(v);
        glm::vec3 c;
        for (int i = 0; i < 3; ++i) {
            if (!v[size_t(i)].is_number()) return "component " + std::to_string(i) + ": expected a number, not " + valueText(v[size_t(i)]);
            double x = v[size_t(i)].get<double>();
            if (!(x >= key.minValue && x <= key.maxValue)) return "component " + std::to_string(i) + " outside [0, 1]";
            c[i] = float(x);
        }
        m.glint.color = c;
        return "";
    }
    // textureInfo: {"index": i, "texCoord": 0}; a bare integer in extras (Blender custom properties are flat).
    long long index = -1;
    auto readIndex = [&](const GltfValue& i) {
        if (!i.is_number_integer()) return false;
        index = i.is_number_unsigned() ? (i.get<uint64_t>() > uint64_t(1) << 31 ? (1LL << 31) : (long long)i.get<uint64_t>()) : i.get<int64_t>();
        return true;
    };
    if (v.is_number_integer()) {
        readIndex(v);
    } else if (v.is_object()) {
        for (auto it = v.begin(); it != v.end(); ++it)
            if (it.key() != "index" && it.key() != "texCoord" && it.key() != "extensions" && it.key() != "extras")
                return "unknown key '" + it.key().substr(0, 64) + "'";
        if (!v.contains("index") || !readIndex(v["index"])) return "needs an integer \"index\"";
        if (v.contains("texCoord") && !(v["texCoord"].is_number_integer() && v["texCoord"].get<int64_t>() == 0))
            return "only texCoord 0 is supported";
    } else {
        return "expected a textureInfo object, not " + valueText(v);
    }
    if (index < 0) return "texture index " + std::to_string(index) + " is negative";
    if (index > (1LL << 30)) return "texture index " + std::to_string(index) + " does not exist";
    int t = texture(int(index));
    if (t == -2) return "texture index " + std::to_string(index) + " does not exist";
    m.glintMaskTexture = t;
    return "";
}

const GlintKey* findKey(const std::string& name) {
    for (const GlintKey& k : glintKeys())
        if (name == k.name) return &k;
    return nullptr;
}

std::string knownKeys() {
    std::string all;
    for (const GlintKey& k : glintKeys()) all += (all.empty() ? "" : ", ") + std::string(k.name);
    return all;
}

}  // namespace

void readGlintMaterial(const GltfValue* material, Material& m, const std::string& file,
                       const std::function<int(int)>& texture, const std::function<void(const std::string&)>& warn) {
    const std::string where = file + ": material '" + m.name + "': ";
    const GltfValue* extras = jsonMember(material, "extras");
    if (const GltfValue* ext = jsonMember(jsonMember(material, "extensions"), kGlintExtension)) {
        if (!ext->is_object()) throw Error(where + kGlintExtension + ": expected an object, not " + valueText(*ext));
        for (auto it = ext->begin(); it != ext->end(); ++it) {
            const std::string& name = it.key();
            if (name == "extensions" || name == "extras") continue;   // allowed on every glTF object
            const GlintKey* key = findKey(name);
            if (!key) throw Error(where + kGlintExtension + "." + name.substr(0, 64) + ": unknown key (known: " + knownKeys() + ")");
            std::string problem = applyKey(*key, *it, m, texture);
            if (!problem.empty()) throw Error(where + kGlintExtension + "." + name + ": " + problem);
        }
        m.glinty = true;
        if (extras && extras->is_object() && (extras->contains(kGlintExtension) || [&] {
                for (auto it = extras->begin(); it != extras->end(); ++it)
                    if (it.key().rfind("glint_", 0) == 0) return true;
                return false;
            }()))
            warn("material '" + m.name + "': glint keys in extras are ignored (the " + kGlintExtension + " extension wins)");
        return;
    }
    if (!extras || !extras->is_object()) return;
    // Extras are free-form (other tools write there too): problems warn and skip the key instead of failing.
    std::vector<std::pair<std::string, const GltfValue*>> entries;
    std::string prefix = "extras.";
    if (const GltfValue* nested = jsonMember(extras, kGlintExtension)) {
        if (!nested->is_object()) {
            warn("material '" + m.name + "': extras." + kGlintExtension + ": expected an object; ignored");
            return;
        }
        prefix = std::string("extras.") + kGlintExtension + ".";
        for (auto it = nested->begin(); it != nested->end(); ++it) entries.push_back({it.key(), &*it});
    } else {
        for (auto it = extras->begin(); it != extras->end(); ++it)
            if (it.key().rfind("glint_", 0) == 0) entries.push_back({it.key().substr(6), &*it});
        prefix = "extras.glint_";
    }
    if (entries.empty()) return;
    m.glinty = true;
    for (const auto& [name, value] : entries) {
        const GlintKey* key = findKey(name);
        std::string problem = key ? applyKey(*key, *value, m, texture) : "unknown key (known: " + knownKeys() + ")";
        if (!problem.empty()) warn("material '" + m.name + "': " + prefix + name.substr(0, 64) + ": " + problem + "; ignored");
    }
}

void measureSurfacePerUvArea(Scene& scene) {
    std::vector<double> world(scene.materials.size(), 0.0), uv(scene.materials.size(), 0.0);
    for (const Instance& instance : scene.instances) {
        if (instance.material >= scene.materials.size()) continue;
        const MeshData& mesh = scene.meshes[instance.mesh];
        if (mesh.uvs.size() != mesh.positions.size()) continue;
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
            glm::vec3 pa = glm::vec3(instance.transform * glm::vec4(mesh.positions[a], 1.0f));
            glm::vec3 pb = glm::vec3(instance.transform * glm::vec4(mesh.positions[b], 1.0f));
            glm::vec3 pc = glm::vec3(instance.transform * glm::vec4(mesh.positions[c], 1.0f));
            glm::vec2 ua = mesh.uvs[a], ub = mesh.uvs[b], uc = mesh.uvs[c];
            double worldArea = 0.5 * double(glm::length(glm::cross(pb - pa, pc - pa)));
            glm::vec2 e1 = ub - ua, e2 = uc - ua;
            double uvArea = 0.5 * std::abs(double(e1.x) * e2.y - double(e1.y) * e2.x);
            if (!std::isfinite(worldArea) || !std::isfinite(uvArea)) continue;
            world[instance.material] += worldArea;
            uv[instance.material] += uvArea;
        }
    }
    for (size_t i = 0; i < scene.materials.size(); ++i)
        if (uv[i] > 1e-30 && world[i] > 0.0) scene.materials[i].surfacePerUvArea = float(world[i] / uv[i]);
}

std::optional<int> nodeLight(const GltfValue* node, int nodeIndex, const std::string& file) {
    const GltfValue* ext = jsonMember(jsonMember(node, "extensions"), "KHR_lights_punctual");
    if (!ext) return std::nullopt;
    GltfValueReader r(file + ": nodes[" + std::to_string(nodeIndex) + "].extensions.KHR_lights_punctual.");
    if (!ext->is_object()) r.fail("", "expected an object");
    const GltfValue* light = jsonMember(ext, "light");
    if (!light) r.fail("light", "missing (expected a light index)");
    return int(r.integer(*light, "light", 0, std::numeric_limits<int>::max()));
}

Light punctualLight(const GltfValue& root, int index, const glm::mat4& world, const std::string& file) {
    const GltfValue* lights = jsonMember(jsonMember(jsonMember(&root, "extensions"), "KHR_lights_punctual"), "lights");
    const GltfValue* gl = jsonElement(lights, size_t(index));
    if (!gl)
        throw Error(file + ": KHR_lights_punctual: light index " + std::to_string(index) + " does not exist (have " +
                    std::to_string(lights && lights->is_array() ? lights->size() : 0) + ")");
    GltfValueReader r(file + ": extensions.KHR_lights_punctual.lights[" + std::to_string(index) + "].");
    if (!gl->is_object()) r.fail("", "expected an object");
    // KHR_lights_punctual: type is required; color in [0, 1] (default white), intensity >= 0 (default 1), range > 0.
    Light light;
    const GltfValue* type = jsonMember(gl, "type");
    if (!type || !type->is_string()) r.fail("type", "expected \"directional\", \"point\" or \"spot\"");
    const std::string kind = type->get<std::string>();
    if (const GltfValue* color = jsonMember(gl, "color")) {
        std::vector<double> c = r.numbers(*color, "color", 3, 0.0, 1.0);
        light.color = glm::vec3(float(c[0]), float(c[1]), float(c[2]));
    }
    if (const GltfValue* intensity = jsonMember(gl, "intensity")) light.intensity = float(r.number(*intensity, "intensity", 0.0, 1e12));
    else light.intensity = 1.0f;
    light.range = 0.0f;
    if (const GltfValue* range = jsonMember(gl, "range")) light.range = float(r.number(*range, "range", 0.0, 1e12));   // 0: unlimited
    glm::vec3 axis = glm::vec3(world * glm::vec4(0, 0, -1, 0));
    glm::vec3 position = glm::vec3(world[3]);
    if (!std::isfinite(glm::dot(position, position))) r.fail("", "its node's transform is not finite");
    if (kind == "directional") {
        light.type = LightType::Directional;
        light.vector = -glm::normalize(axis);   // the engine stores the direction towards the light
    } else if (kind == "point" || kind == "spot") {
        light.type = kind == "point" ? LightType::Point : LightType::Spot;
        light.vector = position;
        light.spotDirection = glm::normalize(axis);
        if (kind == "spot") {
            // KHR_lights_punctual: 0 <= innerConeAngle < outerConeAngle <= pi / 2 (defaults 0 and pi / 4).
            const GltfValue* spot = jsonMember(gl, "spot");
            if (spot && !spot->is_object()) r.fail("spot", "expected an object, not " + jsonValueText(*spot));
            double outer = 0.7853981633974483, inner = 0.0;
            if (const GltfValue* v = jsonMember(spot, "outerConeAngle")) outer = r.number(*v, "spot.outerConeAngle", 0.0, 1.5707964);
            if (const GltfValue* v = jsonMember(spot, "innerConeAngle")) inner = r.number(*v, "spot.innerConeAngle", 0.0, 1.5707964);
            if (!(outer > 0.0)) r.fail("spot.outerConeAngle", "must be above 0");
            if (!(inner < outer)) r.fail("spot.innerConeAngle", "must be below outerConeAngle");
            light.innerConeAngle = float(inner);
            light.outerConeAngle = float(outer);
        }
    } else {
        r.fail("type", "'" + kind.substr(0, 64) + "' is not directional, point or spot");
    }
    return light;
}

bool usableLightTransform(const glm::mat4& world) {
    glm::vec3 axis = glm::vec3(world * glm::vec4(0, 0, -1, 0));
    glm::vec3 position = glm::vec3(world[3]);
    return std::isfinite(glm::dot(axis, axis)) && glm::length(axis) >= 1e-12f && std::isfinite(glm::dot(position, position));
}

}  // namespace glimmer
