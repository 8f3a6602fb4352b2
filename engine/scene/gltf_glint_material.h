// The glint material in glTF: the vendor extension GLIMMER_materials_glint on a material, or the same keys in the
// material's extras (Blender writes custom properties there), and KHR_lights_punctual lights. Specification:
// content/README.md "GLIMMER_materials_glint". Kept apart from gltf_loader.cpp, which calls these.
#pragma once
#include <tiny_gltf.h>

#include <functional>
#include <string>
#include <vector>

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
// `texture(index)` turns a glTF texture index into a Scene texture index (-1 when unusable).
void readGlintMaterial(const tinygltf::Material& gm, Material& m, const std::string& file,
                       const std::function<int(int)>& texture, const std::function<void(const std::string&)>& warn);

// Square metres of world surface per unit UV area of each material, measured over its instances (uniform for
// the planar and cylindrical UV layouts of real models; the area-weighted mean otherwise).
void measureSurfacePerUvArea(Scene& scene);

// KHR_lights_punctual light `index` placed by the node's world matrix (lights shine along the node's -Z).
// Throws Error naming the file and the light's key on bad input.
Light punctualLight(const tinygltf::Model& model, int index, const glm::mat4& world, const std::string& file);
// The light index a node carries in its KHR_lights_punctual extension, or -1.
int nodeLight(const tinygltf::Node& node, const std::string& file);

}  // namespace glimmer
