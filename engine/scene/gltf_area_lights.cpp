#include "scene/gltf_area_lights.h"

#include <cmath>
#include <cstring>

#include <limits>

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

Light readLight(const GltfValue& o, const std::string& where) {
    if (!o.is_object()) throw Error(where + ": expected an object, not " + jsonValueText(o));
    const GltfValue* typeValue = jsonMember(&o, "type");
    if (!typeValue || !typeValue->is_string()) throw Error(where + ".type: required, \"rect\", \"disk\" or \"sphere\"");
    const std::string type = typeValue->get<std::string>();
    if (type != "rect" && type != "disk" && type != "sphere")
        throw Error(where + ".type: '" + type.substr(0, 64) + "' is not \"rect\", \"disk\" or \"sphere\"");
    Light light;
    light.type = typeOf(type);
    light.spotDirection = {0.0f, 0.0f, -1.0f};
    light.right = {1.0f, 0.0f, 0.0f};
    bool hasWidth = false, hasHeight = false, hasRadius = false;
    for (const auto& [name, v] : o.items()) {
        if (name == "extensions" || name == "extras" || name == "type") continue;
        const AreaLightKey* key = findKey(name);
        const std::string at = where + "." + name.substr(0, 64);
        if (!key) throw Error(at + ": unknown key (known: " + knownKeys() + ")");
        if (!appliesTo(*key, type)) throw Error(at + ": does not apply to a " + type + " light (only " + key->shapes + ")");
        const std::string kind = key->type;
        if (kind == "string") {
            if (!v.is_string()) throw Error(at + ": expected a string");
        } else if (kind == "boolean") {
            if (!v.is_boolean()) throw Error(at + ": expected true or false, not " + jsonValueText(v));
            light.twoSided = v.get<bool>();
        } else if (kind == "color") {
            if (!v.is_array() || v.size() != 3) throw Error(at + ": expected [r, g, b]");
            for (size_t i = 0; i < 3; ++i) {
                const GltfValue& c = v[i];
                // JSON numbers of any width are read as the number they are (scene/gltf_json.h).
                const double x = c.is_number() ? c.get<double>() : -1.0;
                if (!c.is_number() || !(x >= 0.0 && x <= 1.0))
                    throw Error(at + "[" + std::to_string(i) + "]: expected a number in [0, 1], not " + jsonValueText(c));
                light.color[int(i)] = float(x);
            }
        } else {   // number
            if (!v.is_number()) throw Error(at + ": expected a number, not " + jsonValueText(v));
            const double x = v.get<double>();
            bool inside = std::isfinite(x) && x <= key->maxValue && (key->exclusiveMin ? x > key->minValue : x >= key->minValue);
            if (!inside) throw Error(at + ": value " + jsonValueText(v) + " outside " + rangeText(*key));
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

std::vector<Light> readAreaLights(const GltfValue& root, const std::string& file) {
    const GltfValue* ext = jsonMember(jsonMember(&root, "extensions"), kAreaLightExtension);
    if (!ext) return {};
    const std::string where = file + ": " + kAreaLightExtension;
    if (!ext->is_object()) throw Error(where + ": expected an object");
    for (const auto& [key, value] : ext->items())
        if (key != "lights" && key != "extensions" && key != "extras")
            throw Error(where + "." + key.substr(0, 64) + ": unknown key (known: lights)");
    const GltfValue* list = jsonMember(ext, "lights");
    if (!list || !list->is_array()) throw Error(where + ".lights: expected an array");
    if (list->size() > kMaxAreaLights)
        throw Error(where + ".lights: " + std::to_string(list->size()) + " lights, over the limit of " +
                    std::to_string(kMaxAreaLights));
    std::vector<Light> lights;
    lights.reserve(list->size());
    for (size_t i = 0; i < list->size(); ++i)
        lights.push_back(readLight((*list)[i], where + ".lights[" + std::to_string(i) + "]"));
    return lights;
}

std::optional<int> nodeAreaLight(const GltfValue* node, int nodeIndex, const std::string& file) {
    const GltfValue* ext = jsonMember(jsonMember(node, "extensions"), kAreaLightExtension);
    if (!ext) return std::nullopt;
    GltfValueReader r(file + ": nodes[" + std::to_string(nodeIndex) + "].extensions." + kAreaLightExtension + ".");
    if (!ext->is_object()) r.fail("", "expected an object");
    const GltfValue* light = jsonMember(ext, "light");
    if (!light) r.fail("light", "missing (expected a light index)");
    return int(r.integer(*light, "light", 0, std::numeric_limits<int>::max()));
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
