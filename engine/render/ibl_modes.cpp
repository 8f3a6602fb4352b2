#include "render/ibl_modes.h"

#include <algorithm>
#include <cctype>

#include "core/error.h"
#include "glints/wang2020_environment.h"

namespace glimmer {

const std::vector<IblMode>& iblModes() {
    static const std::vector<IblMode> modes = {
        {"prefiltered", "Split-sum prefiltered environment (default)", "IBL_MODE_PREFILTERED", "ibl/prefiltered.glsl",
         "Karis 2013, Real Shading in Unreal Engine 4", {}, false, nullptr},
        {"wang2020", "Wang, Deng & Holzschuch 2020 (prefiltered glint table, with --method wang2020)",
         "IBL_MODE_WANG2020", "ibl/wang2020.glsl",
         "Wang, Deng & Holzschuch 2020, Real-time glints rendering with prefiltered discrete stochastic microfacets, "
         "Computer Graphics Forum 39(6)",
         {}, false, createWang2020EnvironmentResources},
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

std::string iblParamsGlsl(const IblMode& mode) {
    std::string glsl = "layout(std140, binding = 5) uniform IblParamBlock { vec4 u_iblParams[" +
                       std::to_string(kMaxIblParams / 4) + "]; };\n";
    static const char* lanes = "xyzw";
    for (size_t i = 0; i < mode.params.size(); ++i) {
        std::string upper = mode.params[i].name;
        std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
        glsl += "#define IBL_" + upper + " u_iblParams[" + std::to_string(i / 4) + "]." + lanes[i % 4] + "\n";
    }
    return glsl;
}

std::vector<float> packIblParams(const IblMode& mode, const ParamValues& values) {
    std::vector<float> packed(kMaxIblParams, 0.0f);
    for (size_t i = 0; i < mode.params.size() && i < packed.size(); ++i) packed[i] = paramOr(values, mode.params[i]);
    return packed;
}

}  // namespace glimmer
