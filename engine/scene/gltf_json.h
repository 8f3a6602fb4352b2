// The glTF JSON read directly with nlohmann::json, for what tinygltf 2.7 reads lossily (it stays the loader of
// everything else: accessors, buffers, images, the node graph):
//   - every JSON integer becomes an int: core integer properties through GetInt and every extension or extras
//     value through ParseJsonAsValue cast int64 to int, so "density": 4294967296 read as 0 and
//     "emissiveStrength": 4294967297 as 1;
//   - ParseExtensionsProperty drops an extension whose value is not an object ("GLIMMER_materials_glint": 5), and
//     ParseJsonAsValue drops null entries of arrays and objects ([1, null, 0.5, 0.2] became [1, 0.5, 0.2]);
//   - an optional core number of the wrong type keeps its default ("intensity": "bright" gave 1).
// Two ways were possible: pre-scan the JSON and refuse every integer tinygltf would wrap, or read the values
// ourselves. Both are used, each where it is exact: the extensions the loader understands (GLIMMER_materials_glint,
// KHR_materials_clearcoat, KHR_materials_emissive_strength, KHR_texture_transform, KHR_lights_punctual, GLIMMER_lights_area) and the
// glint extras are read from this JSON, so a wide integer is read as the number it is (a density of 2^32 facets
// per square metre is legal) and a null or a wrong type is an error naming the key; the core properties tinygltf
// reads as int (indices, enums, texCoord) are pre-scanned and an integer outside 32 bits is an error naming the
// key (no valid index or enum is that large), because reading them ourselves would mean re-implementing the
// loader. docs/hostile_input.md repeats this.
#pragma once
#include <nlohmann/json.hpp>

#include <string>

namespace glimmer {

using GltfValue = nlohmann::json;

// The JSON of a .gltf file, or of the JSON chunk of a .glb (`bytes` as read; tinygltf has accepted them).
// Strings longer than 64 KiB (data: URIs of buffers and images, which tinygltf decodes) are left out, so the copy
// stays small. Throws Error naming `file` when the JSON cannot be read.
GltfValue parseGltfJson(const unsigned char* bytes, size_t size, bool binary, const std::string& file);

// The pre-scan: outside "extensions" and "extras", every integer must fit in 32 bits unless its key is one that
// tinygltf reads as a double or as size_t (byteOffset, byteLength, byteStride, count outside sparse); and every
// extension the loader understands, wherever it appears, must be an object. Throws Error "<file>: <key path>: ...".
void checkGltfJson(const GltfValue& root, const std::string& file);

// The member `key` of `object` when `object` is an object holding it, else nullptr (never throws).
const GltfValue* jsonMember(const GltfValue* object, const char* key);
// Element `index` of `array` when it is an array that long, else nullptr.
const GltfValue* jsonElement(const GltfValue* array, size_t index);

// Reads values with errors "<prefix><key>: <problem>", prefix like "model.gltf: materials[0].extensions.X.".
class GltfValueReader {
public:
    explicit GltfValueReader(std::string prefix) : prefix_(std::move(prefix)) {}
    [[noreturn]] void fail(const std::string& key, const std::string& problem) const;
    // A JSON number (integers of any width included) within [lo, hi]; not null, not a string.
    double number(const GltfValue& value, const std::string& key, double lo, double hi) const;
    // A JSON integer within [lo, hi], compared in 64 bits (never wrapped).
    long long integer(const GltfValue& value, const std::string& key, long long lo, long long hi) const;
    // [n numbers] each within [lo, hi].
    std::vector<double> numbers(const GltfValue& value, const std::string& key, size_t n, double lo, double hi) const;
    const std::string& prefix() const { return prefix_; }

private:
    std::string prefix_;
};

// "4294967296", "1.5", "null", "\"bright\"": how errors quote a value (at most 40 characters).
std::string jsonValueText(const GltfValue& value);

}  // namespace glimmer
