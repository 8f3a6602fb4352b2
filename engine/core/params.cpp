#include "core/params.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.h"

namespace glimmer {

float parseParamValue(const ParamSpec& spec, const std::string& text, const std::string& flag,
                      const std::string& key) {
    for (size_t i = 0; i < spec.choices.size(); ++i)
        if (spec.choices[i] == text) return static_cast<float>(i);
    char* end = nullptr;
    float value = std::strtof(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value)) {
        std::string expected = "a number";
        if (!spec.choices.empty()) {
            expected = "one of";
            for (const auto& c : spec.choices) expected += " " + c;
        }
        throw UsageError(flag + ": " + key + "=" + text + " is not " + expected);
    }
    if (value < spec.minValue || value > spec.maxValue) {
        std::ostringstream message;
        message << flag << ": " << key << "=" << text << " is outside [" << spec.minValue << ", " << spec.maxValue
                << "]";
        throw UsageError(message.str());
    }
    if (spec.integer || !spec.choices.empty()) value = std::round(value);
    return value;
}

std::string formatParamValue(const ParamSpec& spec, float value) {
    int index = static_cast<int>(std::lround(value));
    if (!spec.choices.empty() && index >= 0 && index < static_cast<int>(spec.choices.size()))
        return spec.choices[index];
    std::ostringstream out;
    out << value;
    return out.str();
}

float paramOr(const ParamValues& values, const ParamSpec& spec) {
    auto it = values.find(spec.name);
    return it == values.end() ? spec.defaultValue : it->second;
}

}  // namespace glimmer
