// The table of environment-integration ("IBL") modes: how the lighting pass turns the environment map into
// reflected radiance. Each entry names its shader file (shaders/<file>, defining iblRadiance(), see
// shaders/environment/ibl/README.md), the define that selects it, its parameters (--set ibl.<name>=V, read in GLSL as
// IBL_<NAME>) and whether it is a Monte Carlo estimator whose frames are accumulated (--spp, the still window).
// Adding a mode: write its shader file, add a function returning its IblMode in ibl_modes.cpp, list it in iblModes().
#pragma once
#include "common/bindings.glsl"
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/params.h"
#include "glints/methods.h"

namespace glimmer {

struct Scene;
namespace ibl {
class SceneCapture;
}

// GPU resources of a mode (sample patterns, tables). Created when the mode is selected; bind() runs before every
// lighting pass. Modes use the texture units and buffer bindings UNIT_/BINDING_IBL_FIRST..LAST of shaders/common/bindings.glsl.
class IblModeResources {
public:
    virtual ~IblModeResources() = default;
    // Optional: runs before any pass of a frame with the mode's parameter values, the scene, the environment's
    // source cube (0 when none) and a way to render the scene (per-object environment maps), so resources that
    // depend on them (sample patterns per material, filtered copies of the environment) rebuild when they change.
    virtual void prepare(const ParamValues& values, const Scene& scene, unsigned environmentSource,
                         ibl::SceneCapture& capture) {
        (void)values; (void)scene; (void)environmentSource; (void)capture;
    }
    // Optional: runs after the G-buffer pass with the environment bound, with the glint method's resources (null
    // when the method has none), for data built from both (the wang2020 glint table prefilters the environment
    // with the method's DPF). Returns the passes that ran (name, wall ms) for --stats.
    virtual std::vector<std::pair<std::string, double>> update(const ParamValues& values,
                                                               const GlintMethodResources* methodResources) {
        (void)values; (void)methodResources;
        return {};
    }
    virtual void bind() = 0;
};

struct IblMode {
    std::string id;           // --ibl name, e.g. "prefiltered"
    std::string title;
    std::string define;       // e.g. "IBL_MODE_PREFILTERED"
    std::string shaderFile;   // relative to shaders/, e.g. "environment/ibl/prefiltered.glsl"
    std::string citation;
    std::vector<ParamSpec> params;  // read in GLSL as IBL_<NAME> (upper case)
    bool accumulates = false;       // one estimate per frame; frames with the same view are averaged
    // Methods the mode requires (empty: any); --ibl with another --method is a one-line usage error.
    std::vector<std::string> requiredMethods;
    std::function<std::unique_ptr<IblModeResources>()> createResources;
    // The mode's shader reads the environment through the probe-aware lookups of environment/prefiltered_lookup.glsl
    // (envLightingAt, envPrefilteredAt, envRadianceAt): the renderer captures and binds reflection probes for it.
    bool readsProbes = false;
};

const std::vector<IblMode>& iblModes();
// Throws UsageError("--ibl: unknown mode 'x' (known: ...)").
const IblMode& findIblMode(const std::string& id);
// Whether `mode` can run with glint method `methodId` (its requiredMethods are empty or name it).
bool iblModeRunsWith(const IblMode& mode, const std::string& methodId);
// "kemppinen2025" or "a or b": the methods `mode` requires (empty when any will do).
std::string requiredMethodsText(const IblMode& mode);
// Throws UsageError when `mode` cannot run with glint method `methodId`.
void checkIblModeMethod(const IblMode& mode, const std::string& methodId);

// GLSL preamble declaring the mode's parameter block (uniform binding kIblParamBinding) and IBL_<NAME> macros.
std::string iblParamsGlsl(const IblMode& mode);
std::vector<float> packIblParams(const IblMode& mode, const ParamValues& values);

constexpr unsigned kIblParamBinding = BINDING_IBL_PARAMS;
constexpr int kMaxIblParams = 32;

}  // namespace glimmer
