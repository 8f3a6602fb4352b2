#include "render/ibl_modes.h"

#include <algorithm>

#include "core/error.h"
#include "glints/wang2020_environment.h"

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

// Wang, Deng & Holzschuch 2020, Sec. 4.2: the prefiltered 4D glint table combined with the glint method's per-pixel
// particle count (shaders/ibl/wang2020.glsl; prefilter pass engine/glints/wang2020_environment.cpp).
static IblMode wang2020Mode() {
    return {"wang2020",
            "Wang et al. 2020 prefiltered glint table (needs --method wang2020)",
            "IBL_MODE_WANG2020",
            "ibl/wang2020.glsl",
            "Wang, Deng & Holzschuch 2020, Real-time glints rendering with prefiltered discrete stochastic "
            "microfacets, Computer Graphics Forum 39(6)",
            {},
            false,
            {"wang2020"},
            createWang2020EnvironmentResources};
}

const std::vector<IblMode>& iblModes() {
    static const std::vector<IblMode> modes = {
        prefilteredMode(),
        wang2020Mode(),
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
