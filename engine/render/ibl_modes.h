// The table of environment-integration ("IBL") modes: how the lighting pass turns the environment map into
// reflected radiance. Each entry names its shader file (shaders/<file>, defining iblRadiance(), see
// shaders/ibl/README.md), the define that selects it, its parameters (--set ibl.<name>=V, read in GLSL as
// IBL_<NAME>) and whether it is a Monte Carlo estimator whose frames are accumulated (--spp, the still window).
// Adding a mode: write its shader file, add a function returning its IblMode in ibl_modes.cpp, list it in iblModes().
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/params.h"
#include "glints/methods.h"

namespace glimmer {

// GPU resources of a mode (sample patterns, tables). Created when the mode is selected; bind() runs before every
// lighting pass. Modes use texture units 16-23 and buffer bindings 16-23.
using IblModeResources = GlintMethodResources;

struct IblMode {
    std::string id;           // --ibl name, e.g. "prefiltered"
    std::string title;
    std::string define;       // e.g. "IBL_MODE_PREFILTERED"
    std::string shaderFile;   // relative to shaders/, e.g. "ibl/prefiltered.glsl"
    std::string citation;
    std::vector<ParamSpec> params;  // read in GLSL as IBL_<NAME> (upper case)
    bool accumulates = false;       // one estimate per frame; frames with the same view are averaged
    // Methods the mode requires (empty: any); --ibl with another --method is a one-line usage error.
    std::vector<std::string> requiredMethods;
    std::function<std::unique_ptr<IblModeResources>()> createResources;
};

const std::vector<IblMode>& iblModes();
// Throws UsageError("--ibl: unknown mode 'x' (known: ...)").
const IblMode& findIblMode(const std::string& id);
// Throws UsageError when `mode` cannot run with glint method `methodId`.
void checkIblModeMethod(const IblMode& mode, const std::string& methodId);

// GLSL preamble declaring the mode's parameter block (uniform binding kIblParamBinding) and IBL_<NAME> macros.
std::string iblParamsGlsl(const IblMode& mode);
std::vector<float> packIblParams(const IblMode& mode, const ParamValues& values);

constexpr unsigned kIblParamBinding = 5;
constexpr int kMaxIblParams = 32;

}  // namespace glimmer
