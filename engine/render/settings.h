// Everything that selects or tunes a render apart from the scene and camera: the glint method and its
// parameters, the common parameters (exposure, lights, material overrides) and the debug view.
#pragma once
#include <string>
#include <vector>

#include "core/params.h"
#include "scene/scene.h"

namespace glimmer {

struct GlintMethod;

// Parameters shared by every method. Entries marked sceneDefault take the scene's value unless set.
struct CommonParam {
    ParamSpec spec;
    bool sceneDefault = false;
};
const std::vector<CommonParam>& commonParams();

struct RenderSettings {
    std::string method = "smooth";
    ParamValues common;                         // keys of commonParams()
    std::map<std::string, ParamValues> methods; // method id -> its parameter values
    int debugView = 0;                          // AovInfo::viewId
    std::string ibl = "prefiltered";            // environment-integration mode (environment/ibl/ibl_modes.h)
    std::map<std::string, ParamValues> iblValues;  // mode id -> its parameter values (--set ibl.<name>=V)

    float common_(const std::string& name) const;  // value or default of a common parameter
    bool isSet(const std::string& name) const { return common.count(name) != 0; }
    const ParamValues& methodValues(const std::string& id) const;
    const ParamValues& iblModeValues(const std::string& id) const;

    // Applies one --set KEY=VALUE. KEY is a common parameter, "<method>.<param>", "ibl.<param>" (a parameter of
    // the current IBL mode), or a bare parameter of the current method. Throws UsageError naming --set and the key.
    void apply(const std::string& assignment);
};

// Returns the scene with material and light overrides of `settings` applied.
void applySceneOverrides(const RenderSettings& settings, Scene& scene);

// Text for `glimmer render --list-params`.
std::string describeParams();

}  // namespace glimmer
