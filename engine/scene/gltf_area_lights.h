// The vendor glTF extension GLIMMER_lights_area: rectangle, disk and sphere lights placed by nodes, in the style of
// KHR_lights_punctual (a list of lights at the top level, nodes refer to one by index; a light shines along its
// node's -Z, its width along +X and its height along +Y; sizes are metres and, like KHR_lights_punctual's range and
// cones, not scaled by the node). Specification: content/README.md "GLIMMER_lights_area". Kept apart from
// gltf_loader.cpp, which calls these.
#pragma once
#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

#include "scene/gltf_json.h"
#include "scene/scene.h"

namespace glimmer {

inline constexpr const char* kAreaLightExtension = "GLIMMER_lights_area";
// More lights than any scene shades (the lighting pass loops over all of them per pixel); checked before the list is
// read.
inline constexpr size_t kMaxAreaLights = 4096;

// The keys of one light of the extension, their JSON types and ranges (one table for the loader, the docs and the
// tests). Numbers in [minValue, maxValue]; exclusiveMin: minValue itself is refused.
struct AreaLightKey {
    const char* name;       // e.g. "width"
    const char* type;       // "type" (rect, disk or sphere), "string", "number", "color" ([r, g, b]) or "boolean"
    double minValue, maxValue;
    bool exclusiveMin;
    const char* shapes;     // the light types it applies to ("rect disk sphere", "rect", ...)
    const char* meaning;
};
const std::vector<AreaLightKey>& areaLightKeys();

// The extension's lights, read from the file's JSON like the other extensions (scene/gltf_json.h: integers of any
// width, nulls and wrong types are errors, not wrapped or dropped); an empty list when the file does not use it.
// Throws Error naming the file and the key: "<file>: GLIMMER_lights_area.lights[2].width: value -1 outside (0, 10000]".
std::vector<Light> readAreaLights(const GltfValue& root, const std::string& file);
// The light index node `nodeIndex` carries in its GLIMMER_lights_area extension, if any (throws Error on a bad value).
std::optional<int> nodeAreaLight(const GltfValue* node, int nodeIndex, const std::string& file);
// Light `index` of `lights` placed by the node's world matrix; throws Error naming the file and the index when it
// does not exist or the transform is singular.
Light placeAreaLight(const std::vector<Light>& lights, int index, const glm::mat4& world, const std::string& file);

}  // namespace glimmer
