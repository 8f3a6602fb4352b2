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

// Monte Carlo modes of issue 5: `seed` offsets the random streams so that two renders are independent (a
// reference image must not share samples with the render it judges).
static ParamSpec seedParam() {
    return {"seed", 0.0f, 0.0f, 1e6f, "random stream offset: renders with different seeds are independent",
            {}, true, false};
}

// Smooth-NDF importance sampling (shaders/ibl/ndf_is.glsl): the comparison baseline, any glint method.
static IblMode ndfIsMode() {
    return {"ndf-is",
            "Monte Carlo, half vectors sampled from the smooth NDF",
            "IBL_MODE_NDF_IS",
            "ibl/ndf_is.glsl",
            "Walter et al. 2007 (NDF sampling, Eq. 28-29, 35-36); the comparison of Kemppinen et al. 2025, Fig. 7",
            {seedParam()},
            true,
            {},
            nullptr};
}

// Glinty-NDF importance sampling (shaders/ibl/glint_is.glsl): Algorithm 2 of Kemppinen et al. 2025.
static IblMode glintIsMode() {
    return {"glint-is",
            "Monte Carlo, half vectors sampled from the filtered glinty NDF",
            "IBL_MODE_GLINT_IS",
            "ibl/glint_is.glsl",
            "Kemppinen et al. 2025, Evaluating and Sampling Glinty NDFs in Constant Time, Sec. 3.3.5, Algorithm 2",
            {seedParam()},
            true,
            {"kemppinen2025"},
            nullptr};
}

const std::vector<IblMode>& iblModes() {
    static const std::vector<IblMode> modes = {
        prefilteredMode(),
        ndfIsMode(),
        glintIsMode(),
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
