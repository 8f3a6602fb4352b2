// The glint material in glTF: the vendor extension GLIMMER_materials_glint on a material, or the same keys in the
// material's extras (Blender writes custom properties there), and KHR_lights_punctual lights. Specification:
// content/README.md "GLIMMER_materials_glint". Kept apart from gltf_loader.cpp, which calls these.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "scene/gltf_json.h"
#include "scene/scene.h"

namespace glimmer {

inline constexpr const char* kGlintExtension = "GLIMMER_materials_glint";

// The extension's keys, their JSON types and ranges (one table for the loader, the docs and the tests).
struct GlintKey {
    const char* name;        // as in the extension, e.g. "density"
    const char* type;        // "number", "color" ([r, g, b]) or "textureInfo"
    double minValue, maxValue;
    const char* meaning;
};
const std::vector<GlintKey>& glintKeys();

// Reads the extension (bad input: throws Error "<file>: material '<name>': GLIMMER_materials_glint.<key>: ...")
// or, without it, the extras (`glint_<key>` entries, or a `GLIMMER_materials_glint` object with the extension's
// keys; bad input: `warn` with the same line and the key is ignored). Sets m.glinty when either is present.
// `material` is the material's object in the file's JSON (scene/gltf_json.h: read there, not through tinygltf,
// which wraps wide integers and drops nulls and non-object extensions). `texture(index)` turns a glTF texture
// index into a Scene texture index (-1 when unusable, -2 when it does not exist).
void readGlintMaterial(const GltfValue* material, Material& m, const std::string& file,
                       const std::function<int(int)>& texture, const std::function<void(const std::string&)>& warn);

// Square metres of world surface per unit UV area of each material, measured over its instances (uniform for
// the planar and cylindrical UV layouts of real models; the area-weighted mean otherwise).
void measureSurfacePerUvArea(Scene& scene);

// KHR_lights_punctual light `index` of the file's JSON `root`, placed by the node's world matrix (lights shine
// along the node's -Z). Throws Error naming the file and the light's key on bad input (a wrong type, a null, a
// value out of range); usableLightTransform(world) must hold.
Light punctualLight(const GltfValue& root, int index, const glm::mat4& world, const std::string& file);
// The light index node `nodeIndex` carries in its KHR_lights_punctual extension, if any (from the JSON).
std::optional<int> nodeLight(const GltfValue* node, int nodeIndex, const std::string& file);
// A node transform a light can use: finite, with a direction (a zero scale hides the node: its light is skipped
// with a warning, like its mesh).
bool usableLightTransform(const glm::mat4& world);

}  // namespace glimmer
