#include "scene/gltf_glint_material.h"

#include <cmath>
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

// Applies one key's value; returns an error text ("" when accepted).
std::string applyKey(const GlintKey& key, const tinygltf::Value& v, Material& m, const std::function<int(int)>& texture) {
    const std::string type = key.type;
    if (type == "number") {
        if (!v.IsNumber()) return "expected a number";
        double x = v.GetNumberAsDouble();
        if (!(x >= key.minValue && x <= key.maxValue))
            return "value " + std::to_string(x) + " outside [" + std::to_string(key.minValue) + ", " +
                   std::to_string(key.maxValue) + "]";
        std::string name = key.name;
        if (name == "density") m.glint.density = float(x);
        else if (name == "angularSize") m.glint.angularSize = float(x);
        else if (name == "colorVariation") m.glint.colorVariation = float(x);
        else if (name == "anisotropy") m.glint.anisotropy = float(x);
        return "";
    }
    if (type == "color") {
        if (!v.IsArray() || v.ArrayLen() != 3) return "expected [r, g, b]";
        glm::vec3 c;
        for (int i = 0; i < 3; ++i) {
            if (!v.Get(i).IsNumber()) return "expected [r, g, b] numbers";
            double x = v.Get(i).GetNumberAsDouble();
            if (!(x >= key.minValue && x <= key.maxValue)) return "component " + std::to_string(i) + " outside [0, 1]";
            c[i] = float(x);
        }
        m.glint.color = c;
        return "";
    }
    // textureInfo: {"index": i, "texCoord": 0}; a bare integer in extras (Blender custom properties are flat).
    int index = -1;
    if (v.IsInt()) {
        index = v.GetNumberAsInt();
    } else if (v.IsObject()) {
        for (const std::string& k : v.Keys())
            if (k != "index" && k != "texCoord" && k != "extensions" && k != "extras") return "unknown key '" + k + "'";
        if (!v.Has("index") || !v.Get("index").IsInt()) return "needs an integer \"index\"";
        index = v.Get("index").GetNumberAsInt();
        if (v.Has("texCoord") && !(v.Get("texCoord").IsInt() && v.Get("texCoord").GetNumberAsInt() == 0))
            return "only texCoord 0 is supported";
    } else {
        return "expected a textureInfo object";
    }
    if (index < 0) return "texture index " + std::to_string(index) + " is negative";
    int t = texture(index);
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

void readGlintMaterial(const tinygltf::Material& gm, Material& m, const std::string& file,
                       const std::function<int(int)>& texture, const std::function<void(const std::string&)>& warn) {
    const std::string where = file + ": material '" + m.name + "': ";
    if (auto it = gm.extensions.find(kGlintExtension); it != gm.extensions.end()) {
        const tinygltf::Value& ext = it->second;
        if (!ext.IsObject()) throw Error(where + kGlintExtension + ": expected an object");
        for (const std::string& name : ext.Keys()) {
            if (name == "extensions" || name == "extras") continue;   // allowed on every glTF object
            const GlintKey* key = findKey(name);
            if (!key) throw Error(where + kGlintExtension + "." + name + ": unknown key (known: " + knownKeys() + ")");
            std::string problem = applyKey(*key, ext.Get(name), m, texture);
            if (!problem.empty()) throw Error(where + kGlintExtension + "." + name + ": " + problem);
        }
        m.glinty = true;
        if (gm.extras.IsObject() && (gm.extras.Has(kGlintExtension) || [&] {
                for (const std::string& k : gm.extras.Keys())
                    if (k.rfind("glint_", 0) == 0) return true;
                return false;
            }()))
            warn("material '" + m.name + "': glint keys in extras are ignored (the " + kGlintExtension + " extension wins)");
        return;
    }
    if (!gm.extras.IsObject()) return;
    // Extras are free-form (other tools write there too): problems warn and skip the key instead of failing.
    std::vector<std::pair<std::string, const tinygltf::Value*>> entries;
    std::string prefix = "extras.";
    if (gm.extras.Has(kGlintExtension)) {
        const tinygltf::Value& nested = gm.extras.Get(kGlintExtension);
        if (!nested.IsObject()) {
            warn("material '" + m.name + "': extras." + kGlintExtension + ": expected an object; ignored");
            return;
        }
        prefix = std::string("extras.") + kGlintExtension + ".";
        for (const std::string& k : nested.Keys()) entries.push_back({k, &nested.Get(k)});
    } else {
        for (const std::string& k : gm.extras.Keys())
            if (k.rfind("glint_", 0) == 0) entries.push_back({k.substr(6), &gm.extras.Get(k)});
        prefix = "extras.glint_";
    }
    if (entries.empty()) return;
    m.glinty = true;
    for (const auto& [name, value] : entries) {
        const GlintKey* key = findKey(name);
        std::string problem = key ? applyKey(*key, *value, m, texture) : "unknown key (known: " + knownKeys() + ")";
        if (!problem.empty()) warn("material '" + m.name + "': " + prefix + name + ": " + problem + "; ignored");
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

int nodeLight(const tinygltf::Node& node, const std::string& file) {
    auto it = node.extensions.find("KHR_lights_punctual");
    if (it == node.extensions.end()) return -1;
    if (!it->second.IsObject() || !it->second.Has("light") || !it->second.Get("light").IsInt())
        throw Error(file + ": node '" + node.name + "': KHR_lights_punctual.light: expected a light index");
    return it->second.Get("light").GetNumberAsInt();
}

Light punctualLight(const tinygltf::Model& model, int index, const glm::mat4& world, const std::string& file) {
    const std::string where = file + ": KHR_lights_punctual.lights[" + std::to_string(index) + "].";
    if (index < 0 || size_t(index) >= model.lights.size())
        throw Error(file + ": KHR_lights_punctual: light index " + std::to_string(index) + " does not exist");
    const tinygltf::Light& gl = model.lights[size_t(index)];
    Light light;
    if (gl.color.size() == 3) {
        for (int c = 0; c < 3; ++c)
            if (!(gl.color[size_t(c)] >= 0.0 && gl.color[size_t(c)] <= 1.0))
                throw Error(where + "color[" + std::to_string(c) + "] is outside [0, 1]");
        light.color = glm::vec3(float(gl.color[0]), float(gl.color[1]), float(gl.color[2]));
    } else if (!gl.color.empty()) {
        throw Error(where + "color: expected [r, g, b]");
    }
    if (!(gl.intensity >= 0.0 && gl.intensity <= 1e12)) throw Error(where + "intensity is negative or not finite");
    light.intensity = float(gl.intensity);
    if (!(gl.range >= 0.0 && std::isfinite(gl.range))) throw Error(where + "range must be positive");
    light.range = float(gl.range);
    glm::vec3 axis = glm::vec3(world * glm::vec4(0, 0, -1, 0));
    glm::vec3 position = glm::vec3(world[3]);
    if (!std::isfinite(glm::dot(axis, axis)) || glm::length(axis) < 1e-12f || !std::isfinite(glm::dot(position, position)))
        throw Error(where + "its node's transform is singular or not finite");
    axis = glm::normalize(axis);
    if (gl.type == "directional") {
        light.type = LightType::Directional;
        light.vector = -axis;   // the engine stores the direction towards the light
    } else if (gl.type == "point" || gl.type == "spot") {
        light.type = gl.type == "point" ? LightType::Point : LightType::Spot;
        light.vector = position;
        light.spotDirection = axis;
        if (gl.type == "spot") {
            // KHR_lights_punctual: 0 <= innerConeAngle < outerConeAngle <= pi / 2.
            double inner = gl.spot.innerConeAngle, outer = gl.spot.outerConeAngle;
            if (!(outer > 0.0 && outer <= 1.5707964)) throw Error(where + "spot.outerConeAngle outside (0, pi/2]");
            if (!(inner >= 0.0 && inner < outer)) throw Error(where + "spot.innerConeAngle outside [0, outerConeAngle)");
            light.innerConeAngle = float(inner);
            light.outerConeAngle = float(outer);
        }
    } else {
        throw Error(where + "type '" + gl.type + "' is not directional, point or spot");
    }
    return light;
}

}  // namespace glimmer
