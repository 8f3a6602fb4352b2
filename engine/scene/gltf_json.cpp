#include "scene/gltf_json.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <set>

#include "core/error.h"

namespace glimmer {
namespace {

constexpr size_t kLongString = size_t(64) << 10;
constexpr int kMaxCoreDepth = 64;   // glTF's core objects nest less than 10 deep

// Core keys tinygltf reads as double (ParseNumberProperty, ParseNumberArrayProperty) or as size_t
// (ParseUnsignedProperty): integers there are not wrapped.
const std::set<std::string>& unwrappedKeys() {
    static const std::set<std::string> keys = {
        "alphaCutoff", "aspectRatio", "baseColorFactor", "emissiveFactor", "innerConeAngle", "outerConeAngle",
        "intensity", "range", "color", "matrix", "max", "min", "metallicFactor", "roughnessFactor", "rotation",
        "scale", "strength", "translation", "weights", "xmag", "ymag", "yfov", "zfar", "znear",
        "byteLength", "byteOffset", "byteStride", "count"};
    return keys;
}

// The extensions the loader reads from this JSON: their values must be objects wherever they appear.
const std::set<std::string>& understoodExtensions() {
    static const std::set<std::string> names = {"GLIMMER_materials_glint", "KHR_materials_clearcoat",
                                                "KHR_materials_emissive_strength", "KHR_texture_transform",
                                                "KHR_lights_punctual", "GLIMMER_lights_area"};
    return names;
}

bool fitsInt32(const GltfValue& v) {
    if (v.is_number_unsigned()) return v.get<uint64_t>() <= uint64_t(std::numeric_limits<int32_t>::max());
    int64_t x = v.get<int64_t>();
    return x >= std::numeric_limits<int32_t>::min() && x <= std::numeric_limits<int32_t>::max();
}

struct CoreScan {
    const std::string& file;

    [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
        throw Error(file + ": " + path + ": " + problem);
    }

    // `key`: the object key this value (or the array holding it) was found under; `insideSparse`: below an
    // accessor's "sparse", whose byteOffset and count tinygltf reads as int.
    void scan(const GltfValue& v, const std::string& path, const std::string& key, bool insideSparse, int depth) const {
        if (depth > kMaxCoreDepth) fail(path, "nested deeper than " + std::to_string(kMaxCoreDepth) + " levels");
        if (v.is_object()) {
            for (auto it = v.begin(); it != v.end(); ++it) {
                const std::string child = path.empty() ? it.key() : path + "." + it.key();
                if (it.key() == "extras") continue;   // free-form; the glint keys there are read as numbers
                if (it.key() == "extensions") {
                    if (!it->is_object()) continue;   // tinygltf ignores it, so does the loader
                    for (auto ext = it->begin(); ext != it->end(); ++ext)
                        if (understoodExtensions().count(ext.key()) && !ext->is_object())
                            fail(child + "." + ext.key(), "expected an object, not " + jsonValueText(*ext));
                    continue;   // extension values are read from the JSON, not through tinygltf
                }
                scan(*it, child, it.key(), insideSparse || it.key() == "sparse", depth + 1);
            }
        } else if (v.is_array()) {
            for (size_t i = 0; i < v.size(); ++i) scan(v[i], path + "[" + std::to_string(i) + "]", key, insideSparse, depth + 1);
        } else if (v.is_number_integer()) {
            bool unwrapped = unwrappedKeys().count(key) && !(insideSparse && (key == "byteOffset" || key == "count"));
            if (!unwrapped && !fitsInt32(v))
                fail(path, "integer " + jsonValueText(v) + " does not fit in 32 bits (no index or enum is that large)");
        }
    }
};

// Builds the DOM like nlohmann's own parser, but keeps strings longer than kLongString as null (data: URIs of
// buffers and images, which tinygltf decodes: a 1 GiB model must not be held twice). Written as a SAX handler
// because nlohmann's callback parser rescans the enclosing array at the end of every object (quadratic: 100k
// objects took seconds).
class DomWithoutLongStrings : public nlohmann::json_sax<GltfValue> {
public:
    explicit DomWithoutLongStrings(GltfValue& root) : root_(root) {}
    bool null() override { return add(GltfValue()); }
    bool boolean(bool v) override { return add(GltfValue(v)); }
    bool number_integer(number_integer_t v) override { return add(GltfValue(v)); }
    bool number_unsigned(number_unsigned_t v) override { return add(GltfValue(v)); }
    bool number_float(number_float_t v, const string_t&) override { return add(GltfValue(v)); }
    bool string(string_t& v) override { return add(v.size() > kLongString ? GltfValue() : GltfValue(std::move(v))); }
    bool binary(binary_t&) override { return add(GltfValue()); }
    bool start_object(std::size_t) override { return push(GltfValue::object()); }
    bool key(string_t& k) override {
        key_ = std::move(k);
        return true;
    }
    bool end_object() override { return pop(); }
    bool start_array(std::size_t) override { return push(GltfValue::array()); }
    bool end_array() override { return pop(); }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

private:
    // Places a value in the container being built (or as the root) and returns where it went.
    GltfValue* place(GltfValue&& value) {
        if (stack_.empty()) {
            root_ = std::move(value);
            return &root_;
        }
        GltfValue& parent = *stack_.back();
        if (parent.is_array()) {
            parent.push_back(std::move(value));
            return &parent.back();
        }
        GltfValue& slot = parent[key_];
        slot = std::move(value);
        return &slot;
    }
    bool add(GltfValue&& value) {
        place(std::move(value));
        return true;
    }
    bool push(GltfValue&& container) {
        stack_.push_back(place(std::move(container)));
        return true;
    }
    bool pop() {
        stack_.pop_back();
        return true;
    }
    GltfValue& root_;
    std::vector<GltfValue*> stack_;
    std::string key_;
};

}  // namespace

GltfValue parseGltfJson(const unsigned char* bytes, size_t size, bool binary, const std::string& file) {
    const unsigned char* json = bytes;
    size_t length = size;
    if (binary) {
        // GLB (glTF 4.4.3): 12-byte header, then the JSON chunk's length, type and data.
        uint32_t chunkLength = 0;
        if (size < 20) throw Error(file + ": GLB too short for its JSON chunk");
        std::memcpy(&chunkLength, bytes + 12, 4);
        if (chunkLength > size - 20) throw Error(file + ": GLB JSON chunk longer than the file");
        json = bytes + 20;
        length = chunkLength;
    }
    GltfValue root;
    DomWithoutLongStrings builder(root);
    const bool parsed = GltfValue::sax_parse(json, json + length, &builder, GltfValue::input_format_t::json, true);
    if (!parsed) root = GltfValue(GltfValue::value_t::discarded);
    if (root.is_discarded() || !root.is_object()) throw Error(file + ": invalid glTF JSON");
    return root;
}

void checkGltfJson(const GltfValue& root, const std::string& file) { CoreScan{file}.scan(root, "", "", false, 0); }

const GltfValue* jsonMember(const GltfValue* object, const char* key) {
    if (!object || !object->is_object()) return nullptr;
    auto it = object->find(key);
    return it == object->end() ? nullptr : &*it;
}

const GltfValue* jsonElement(const GltfValue* array, size_t index) {
    if (!array || !array->is_array() || index >= array->size()) return nullptr;
    return &(*array)[index];
}

std::string jsonValueText(const GltfValue& value) {
    std::string text = value.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return text;
}

void GltfValueReader::fail(const std::string& key, const std::string& problem) const {
    throw Error(prefix_ + key + ": " + problem);
}

double GltfValueReader::number(const GltfValue& value, const std::string& key, double lo, double hi) const {
    if (!value.is_number()) fail(key, "expected a number, not " + jsonValueText(value));
    double x = value.get<double>();   // exact for integers up to 2^53, the nearest double beyond
    if (!(x >= lo && x <= hi)) {
        char range[96];
        std::snprintf(range, sizeof range, " is outside [%g, %g]", lo, hi);
        fail(key, jsonValueText(value) + range);
    }
    return x;
}

long long GltfValueReader::integer(const GltfValue& value, const std::string& key, long long lo, long long hi) const {
    if (!value.is_number_integer()) fail(key, "expected an integer, not " + jsonValueText(value));
    bool inside = value.is_number_unsigned() ? hi >= 0 && value.get<uint64_t>() <= uint64_t(hi) && value.get<uint64_t>() >= uint64_t(std::max(lo, 0LL))
                                             : value.get<int64_t>() >= lo && value.get<int64_t>() <= hi;
    if (!inside) fail(key, jsonValueText(value) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return value.get<long long>();
}

std::vector<double> GltfValueReader::numbers(const GltfValue& value, const std::string& key, size_t n, double lo, double hi) const {
    if (!value.is_array() || value.size() != n)
        fail(key, "expected an array of " + std::to_string(n) + " numbers, not " + jsonValueText(value));
    std::vector<double> out;
    for (size_t i = 0; i < n; ++i) out.push_back(number(value[i], key + "[" + std::to_string(i) + "]", lo, hi));
    return out;
}

}  // namespace glimmer
