// Named parameters with defaults, ranges and meanings. One table drives --set, --list-params, the UI sliders and
// the uniform blocks that shaders read (so C++ and GLSL cannot disagree on names or order).
#pragma once
#include <map>
#include <string>
#include <vector>

namespace glimmer {

struct ParamSpec {
    std::string name;                   // e.g. "log_density"
    float defaultValue = 0.0f;
    float minValue = 0.0f;
    float maxValue = 1.0f;
    std::string meaning;                // one line for --list-params and tooltips
    std::vector<std::string> choices;   // non-empty: an enumeration stored as its index (e.g. ndf: ggx, beckmann)
    bool integer = false;               // slider snaps to integers
    bool logScale = false;              // slider moves in log space (densities)
};

// Values keyed by parameter name. Missing keys mean "use the spec default" (or, for scene overrides, the scene's).
using ParamValues = std::map<std::string, float>;

// Parses `text` for `spec`: a number, or one of spec.choices. Throws UsageError naming `flag` and the key on a
// malformed or out-of-range value.
float parseParamValue(const ParamSpec& spec, const std::string& text, const std::string& flag,
                      const std::string& key);

// Human-readable rendering of a value (choice name for enumerations).
std::string formatParamValue(const ParamSpec& spec, float value);

// Value of `spec` from `values`, else its default.
float paramOr(const ParamValues& values, const ParamSpec& spec);

}  // namespace glimmer
