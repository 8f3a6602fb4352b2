#include "scene/gltf_area_lights.h"

#include <cmath>
#include <cstring>

#include "core/error.h"

namespace glimmer {

const std::vector<AreaLightKey>& areaLightKeys() {
    static const std::vector<AreaLightKey> keys = {
        {"type", "type", 0.0, 0.0, false, "rect disk sphere", "\"rect\", \"disk\" or \"sphere\" (required)"},
        {"name", "string", 0.0, 0.0, false, "rect disk sphere", "free text"},
        {"color", "color", 0.0, 1.0, false, "rect disk sphere", "linear RGB colour of the emission (default white)"},
        {"intensity", "number", 0.0, 1e12, false, "rect disk sphere",
         "candela: along the normal for rect and disk (radiance = intensity / area), in every direction for a "
         "sphere (radiance = intensity / (pi radius^2)); default 1"},
        {"width", "number", 0.0, 1e4, true, "rect", "metres along the node's +X (required)"},
        {"height", "number", 0.0, 1e4, true, "rect", "metres along the node's +Y (required)"},
        {"radius", "number", 0.0, 1e4, true, "disk sphere", "metres (required)"},
        {"twoSided", "boolean", 0.0, 0.0, false, "rect disk", "emits from both faces (default false: towards -Z)"},
        {"range", "number", 0.0, 1e7, false, "rect disk sphere",
         "metres: fades the light to zero at this distance from its centre (KHR_lights_punctual's window); 0 or "
         "absent = infinite"},
    };
    return keys;
}

namespace {

const AreaLightKey* findKey(const std::string& name) {
    for (const AreaLightKey& k : areaLightKeys())
        if (name == k.name) return &k;
    return nullptr;
}

std::string knownKeys() {
    std::string all;
    for (const AreaLightKey& k : areaLightKeys()) all += (all.empty() ? "" : ", ") + std::string(k.name);
    return all;
}

std::string rangeText(const AreaLightKey& key) {
    char text[96];
    std::snprintf(text, sizeof(text), "%s%g, %g]", key.exclusiveMin ? "(" : "[", key.minValue, key.maxValue);
    return text;
}

bool appliesTo(const AreaLightKey& key, const std::string& type) {
    std::string shapes = std::string(" ") + key.shapes + " ";
    return shapes.find(" " + type + " ") != std::string::npos;
}

LightType typeOf(const std::string& name) {
    return name == "rect" ? LightType::Rect : name == "disk" ? LightType::Disk : LightType::Sphere;
}

Light readLight(const tinygltf::Value& o, const std::string& where) {
    if (!o.IsObject()) throw Error(where + ": expected an object");
    if (!o.Has("type") || !o.Get("type").IsString()) throw Error(where + ".type: required, \"rect\", \"disk\" or \"sphere\"");
    const std::string type = o.Get("type").Get<std::string>();
    if (type != "rect" && type != "disk" && type != "sphere")
        throw Error(where + ".type: '" + type + "' is not \"rect\", \"disk\" or \"sphere\"");
    Light light;
    light.type = typeOf(type);
    light.spotDirection = {0.0f, 0.0f, -1.0f};
    light.right = {1.0f, 0.0f, 0.0f};
    bool hasWidth = false, hasHeight = false, hasRadius = false;
    for (const std::string& name : o.Keys()) {
        if (name == "extensions" || name == "extras" || name == "type") continue;
        const AreaLightKey* key = findKey(name);
        const std::string at = where + "." + name;
        if (!key) throw Error(at + ": unknown key (known: " + knownKeys() + ")");
        if (!appliesTo(*key, type)) throw Error(at + ": does not apply to a " + type + " light (only " + key->shapes + ")");
        const tinygltf::Value& v = o.Get(name);
        const std::string kind = key->type;
        if (kind == "string") {
            if (!v.IsString()) throw Error(at + ": expected a string");
        } else if (kind == "boolean") {
            if (!v.IsBool()) throw Error(at + ": expected true or false");
            light.twoSided = v.Get<bool>();
        } else if (kind == "color") {
            if (!v.IsArray() || v.ArrayLen() != 3) throw Error(at + ": expected [r, g, b]");
            for (int i = 0; i < 3; ++i) {
                const tinygltf::Value& c = v.Get(i);
                double x = c.IsNumber() ? c.GetNumberAsDouble() : -1.0;
                if (!c.IsNumber() || !(x >= 0.0 && x <= 1.0))
                    throw Error(at + "[" + std::to_string(i) + "]: expected a number in [0, 1]");
                light.color[i] = float(x);
            }
        } else {   // number
            if (!v.IsNumber()) throw Error(at + ": expected a number");
            double x = v.GetNumberAsDouble();
            bool inside = std::isfinite(x) && x <= key->maxValue && (key->exclusiveMin ? x > key->minValue : x >= key->minValue);
            if (!inside) throw Error(at + ": value " + std::to_string(x) + " outside " + rangeText(*key));
            if (name == "intensity") light.intensity = float(x);
            else if (name == "width") light.width = float(x), hasWidth = true;
            else if (name == "height") light.height = float(x), hasHeight = true;
            else if (name == "radius") light.radius = float(x), hasRadius = true;
            else if (name == "range") light.range = float(x);
        }
    }
    if (light.type == LightType::Rect && (!hasWidth || !hasHeight))
        throw Error(where + (hasWidth ? ".height" : ".width") + ": required for a rect light");
    if (light.type != LightType::Rect && !hasRadius) throw Error(where + ".radius: required for a " + type + " light");
    return light;
}

}  // namespace

std::vector<Light> readAreaLights(const tinygltf::Model& model, const std::string& file) {
    auto it = model.extensions.find(kAreaLightExtension);
    if (it == model.extensions.end()) return {};
    const std::string where = file + ": " + kAreaLightExtension;
    const tinygltf::Value& ext = it->second;
    if (!ext.IsObject()) throw Error(where + ": expected an object");
    for (const std::string& key : ext.Keys())
        if (key != "lights" && key != "extensions" && key != "extras")
            throw Error(where + "." + key + ": unknown key (known: lights)");
    if (!ext.Has("lights") || !ext.Get("lights").IsArray()) throw Error(where + ".lights: expected an array");
    const tinygltf::Value& list = ext.Get("lights");
    std::vector<Light> lights;
    for (size_t i = 0; i < list.ArrayLen(); ++i)
        lights.push_back(readLight(list.Get(int(i)), where + ".lights[" + std::to_string(i) + "]"));
    return lights;
}

int nodeAreaLight(const tinygltf::Node& node, const std::string& file) {
    auto it = node.extensions.find(kAreaLightExtension);
    if (it == node.extensions.end()) return -1;
    if (!it->second.IsObject() || !it->second.Has("light") || !it->second.Get("light").IsInt() ||
        it->second.Get("light").GetNumberAsInt() < 0)
        throw Error(file + ": node '" + node.name + "': " + kAreaLightExtension + ".light: expected a light index");
    return it->second.Get("light").GetNumberAsInt();
}

Light placeAreaLight(const std::vector<Light>& lights, int index, const glm::mat4& world, const std::string& file) {
    const std::string where = file + ": " + kAreaLightExtension + ".lights[" + std::to_string(index) + "]";
    if (index < 0 || size_t(index) >= lights.size())
        throw Error(file + ": " + kAreaLightExtension + ": light index " + std::to_string(index) + " does not exist");
    Light light = lights[size_t(index)];
    glm::vec3 x = glm::vec3(world[0]), z = glm::vec3(world[2]), position = glm::vec3(world[3]);
    glm::vec3 normal = -z;
    if (!std::isfinite(glm::dot(x, x) + glm::dot(z, z) + glm::dot(position, position)) || glm::length(normal) < 1e-12f ||
        glm::length(glm::cross(x, z)) < 1e-12f * glm::length(x) * glm::length(z))
        throw Error(where + ": its node's transform is singular or not finite");
    light.vector = position;
    light.spotDirection = glm::normalize(normal);
    light.right = glm::normalize(x - light.spotDirection * glm::dot(light.spotDirection, x));
    return light;
}

}  // namespace glimmer
