#include "environment/ibl/ibl_modes.h"

#include <algorithm>

#include "core/error.h"
#include "environment/ibl/kurt_ibl_resources.h"
#include "environment/ibl/wang2020_environment.h"

namespace glimmer {

// The split-sum baseline of the environment issue (shaders/environment/prefiltered_lookup.glsl): one deterministic evaluation.
static IblMode prefilteredMode() {
    IblMode mode{"prefiltered",
            "Prefiltered environment (split sum, SH irradiance)",
            "IBL_MODE_PREFILTERED",
            "environment/ibl/prefiltered.glsl",
            "Karis 2013, Real Shading in Unreal Engine 4 (split sum); Ramamoorthi & Hanrahan 2001 (SH irradiance); "
            "Kneiphof & Klein 2025, Real-time Image-based Lighting of Glints (environment glints)",
            {{"glint_levels", 1.0f, 0.0f, 2.0f,
              "environment glints of methods that draw them (deliot2023; Kneiphof & Klein 2025): the environment's "
              "radiance in 4 or 8 log-spaced levels, or off", {"off", "4", "8"}},
             {"glint_black_level", 0.01f, 1e-6f, 100.0f,
              "luminance below which the environment counts as dark for the glint levels (the paper's 10^-2)", {},
              false, true}},
            false,
            {},
            nullptr};
    mode.readsProbes = true;   // local reflections (render/probes/reflection_probes.h)
    return mode;
}

// Wang, Deng & Holzschuch 2020, Sec. 4.2: the prefiltered 4D glint table combined with the glint method's per-pixel
// particle count (shaders/environment/ibl/wang2020.glsl; prefilter pass engine/environment/ibl/wang2020_environment.cpp).
static IblMode wang2020Mode() {
    IblMode mode{"wang2020",
            "Wang et al. 2020 prefiltered glint table (needs --method wang2020)",
            "IBL_MODE_WANG2020",
            "environment/ibl/wang2020.glsl",
            "Wang, Deng & Holzschuch 2020, Real-time glints rendering with prefiltered discrete stochastic "
            "microfacets, Computer Graphics Forum 39(6)",
            {{"prefilter", 0.0f, 0.0f, 1.0f,
              "Eq. 16 estimator: dpf (NDF samples weighted by the tabulated DPF, the paper's; 13-34 % low at "
              "grazing angles) or cone (a direction in the gamma-cone and a particle normal per sample; ours)",
              {"dpf", "cone"}}},
            false,
            {"wang2020"},
            createWang2020EnvironmentResources};
    mode.readsProbes = true;
    return mode;
}

// Monte Carlo modes of issue 5: `seed` offsets the random streams so that two renders are independent (a
// reference image must not share samples with the render it judges).
static ParamSpec seedParam() {
    return {"seed", 0.0f, 0.0f, 1e6f, "random stream offset: renders with different seeds are independent",
            {}, true, false};
}

// Smooth-NDF importance sampling (shaders/environment/ibl/ndf_is.glsl): the comparison baseline, any glint method.
static IblMode ndfIsMode() {
    IblMode mode{"ndf-is",
            "Monte Carlo, half vectors sampled from the smooth NDF",
            "IBL_MODE_NDF_IS",
            "environment/ibl/ndf_is.glsl",
            "Walter et al. 2007 (NDF sampling, Eq. 28-29, 35-36); the comparison of Kemppinen et al. 2025, Fig. 7",
            {seedParam()},
            true,
            {},
            nullptr};
    mode.readsProbes = true;
    return mode;
}

// Glinty-NDF importance sampling (shaders/environment/ibl/glint_is.glsl): Algorithm 2 of Kemppinen et al. 2025.
static IblMode glintIsMode() {
    IblMode mode{"glint-is",
            "Monte Carlo, half vectors sampled from the filtered glinty NDF",
            "IBL_MODE_GLINT_IS",
            "environment/ibl/glint_is.glsl",
            "Kemppinen et al. 2025, Evaluating and Sampling Glinty NDFs in Constant Time, Sec. 3.3.5, Algorithm 2",
            {seedParam()},
            true,
            {"kemppinen2025"},
            nullptr};
    mode.readsProbes = true;
    return mode;
}

// Issue 7: "Real-time Rendering of Glossy Materials with Regular Sampling" (CGI 2014) and its two comparisons,
// all on the Kurt et al. 2010 BRDF (engine/ibl/, shaders/environment/ibl/kurt_brdf.glsl).
static std::vector<ParamSpec> withKurtParams(std::vector<ParamSpec> own) {
    std::vector<ParamSpec> all = ibl::kurtMaterialParams();
    all.insert(all.end(), own.begin(), own.end());
    return all;
}

static IblMode regularMode() {
    std::vector<ParamSpec> params = withKurtParams({
        {"samples", 14.0f, 1.0f, 512.0f, "sample budget: the regular pattern with the closest count is used", {}, true},
        {"xi0", 0.2f, 0.001f, 0.9f, "density threshold xi0 of the pattern (Eq. 11) and of anisotropic rejection", {}, false,
         true},
        {"mip_bias", 0.0f, -4.0f, 4.0f, "added to the per-sample MIP level of Eq. 16"},
        {"ring_rule", 0.0f, 0.0f, 1.0f, "samples per circle: arc (reproduces Fig. 4's counts) or eq13 (literal)",
         {"arc", "eq13"}},
        // Default gauss6: the paper's pyramid (Sec. 3, Table 1; Sec. 8 evaluates with the 6x6 Gaussian).
        {"pyramid", 3.0f, 0.0f, 3.0f,
         "MIP pyramid read: rebuilt with the paper's filters (Sec. 3; default gauss6, as in Sec. 8), or the "
         "environment's own box chain (source)",
         {"source", "box", "gauss4", "gauss6"}},
        {"object_maps", 0.0f, 0.0f, 1.0f, "1: metallic objects reflect their own cube map rendered at their centroid (Sec. 3)",
         {}, true},
        {"object_map_size", 128.0f, 16.0f, 1024.0f, "face size of the per-object maps", {}, true},
    });
    return {"regular",
            "Regular sampling of the MIP-mapped environment (Kurt BRDF)",
            "IBL_MODE_REGULAR",
            "environment/ibl/regular.glsl",
            "Real-time Rendering of Glossy Materials with Regular Sampling, CGI 2014 (Kurt et al. 2010 BRDF)",
            params,
            false,
            {},
            [params] { return std::make_unique<ibl::KurtIblResources>(params, true); }};
}

static IblMode fisMode() {
    std::vector<ParamSpec> params = withKurtParams({
        {"samples", 14.0f, 1.0f, 1024.0f, "importance samples per pixel (Hammersley set, the same for all pixels)", {},
         true},
        {"mip_bias", 0.0f, -4.0f, 4.0f, "added to the filtered-importance-sampling MIP level (which includes +1)"},
        {"pyramid", 0.0f, 0.0f, 3.0f, "MIP pyramid read: the environment's own box chain, or rebuilt (Sec. 3)",
         {"source", "box", "gauss4", "gauss6"}},
        {"object_maps", 0.0f, 0.0f, 1.0f, "1: metallic objects reflect their own cube map rendered at their centroid (Sec. 3)",
         {}, true},
        {"object_map_size", 128.0f, 16.0f, 1024.0f, "face size of the per-object maps", {}, true},
    });
    return {"fis",
            "Filtered importance sampling (Colbert & Krivanek, Kurt BRDF)",
            "IBL_MODE_FIS",
            "environment/ibl/fis.glsl",
            "Colbert & Krivanek 2007, GPU-Based Importance Sampling (GPU Gems 3, ch. 20); Kurt et al. 2010 sampling",
            params,
            false,
            {},
            [params] { return std::make_unique<ibl::KurtIblResources>(params, false); }};
}

static IblMode referenceMode() {
    std::vector<ParamSpec> params = withKurtParams({
        {"samples", 32.0f, 1.0f, 256.0f, "importance samples per pixel and frame (level-0 lookups, accumulated)", {},
         true},
    });
    return {"reference",
            "Monte Carlo reference (Kurt BRDF, accumulated)",
            "IBL_MODE_REFERENCE",
            "environment/ibl/reference.glsl",
            "Kurt et al. 2010 importance sampling (Eq. 6-7, pdf Eq. 10), unfiltered lookups",
            params,
            true,
            {},
            [params] { return std::make_unique<ibl::KurtIblResources>(params, false); }};
}

const std::vector<IblMode>& iblModes() {
    static const std::vector<IblMode> modes = {
        prefilteredMode(),
        ndfIsMode(),
        glintIsMode(),
        regularMode(),
        fisMode(),
        referenceMode(),
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

bool iblModeRunsWith(const IblMode& mode, const std::string& methodId) {
    return mode.requiredMethods.empty() ||
           std::find(mode.requiredMethods.begin(), mode.requiredMethods.end(), methodId) != mode.requiredMethods.end();
}

std::string requiredMethodsText(const IblMode& mode) {
    std::string list;
    for (const std::string& m : mode.requiredMethods) list += (list.empty() ? "" : " or ") + m;
    return list;
}

void checkIblModeMethod(const IblMode& mode, const std::string& methodId) {
    if (iblModeRunsWith(mode, methodId)) return;
    throw UsageError("--ibl " + mode.id + " needs --method " + requiredMethodsText(mode) + " (got " + methodId + ")");
}

std::string iblParamsGlsl(const IblMode& mode) {
    return parameterBlockGlsl(mode.params, kIblParamBinding, "IblParamBlock", "u_iblParams", "IBL_", kMaxIblParams);
}

std::vector<float> packIblParams(const IblMode& mode, const ParamValues& values) {
    return packParameters(mode.params, values, kMaxIblParams);
}

}  // namespace glimmer
