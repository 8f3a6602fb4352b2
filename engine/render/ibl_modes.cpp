#include "render/ibl_modes.h"

#include <algorithm>

#include "core/error.h"

namespace glimmer {

// The split-sum baseline of the environment issue (shaders/common/ibl.glsl): one deterministic evaluation.
static IblMode prefilteredMode() {
    return {"prefiltered",
            "Prefiltered environment (split sum, SH irradiance)",
            "IBL_MODE_PREFILTERED",
            "ibl/prefiltered.glsl",
            "Karis 2013, Real Shading in Unreal Engine 4 (split sum); Ramamoorthi & Hanrahan 2001 (SH irradiance)",
            {},
            false,
            {},
            nullptr};
}

const std::vector<IblMode>& iblModes() {
    static const std::vector<IblMode> modes = {
        prefilteredMode(),
    };
    return modes;
}

const IblMode& findIblMode(const std::string& id) {
    for (const IblMode& m : iblModes())
        if (m.id == id) return m;
    std::string known;
    for (const IblMode& m : iblModes()) known += (known.empty() ? "" : ", ") + m.id;
    throw UsageError("--ibl: unknown mode '" + id + "' (known: " + known + ")");
}

void checkIblModeMethod(const IblMode& mode, const std::string& methodId) {
    if (mode.requiredMethods.empty()) return;
    if (std::find(mode.requiredMethods.begin(), mode.requiredMethods.end(), methodId) != mode.requiredMethods.end())
        return;
    std::string list;
    for (const std::string& m : mode.requiredMethods) list += (list.empty() ? "" : " or ") + m;
    throw UsageError("--ibl " + mode.id + " needs --method " + list + " (got " + methodId + ")");
}

std::string iblParamsGlsl(const IblMode& mode) {
    return parameterBlockGlsl(mode.params, kIblParamBinding, "IblParamBlock", "u_iblParams", "IBL_", kMaxIblParams);
}

std::vector<float> packIblParams(const IblMode& mode, const ParamValues& values) {
    return packParameters(mode.params, values, kMaxIblParams);
}

}  // namespace glimmer
