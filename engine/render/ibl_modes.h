// The table of environment-integration ("IBL") modes: how the lighting pass turns the environment map into
// reflected radiance. Each entry names its shader file (under shaders/), the define that selects it, its parameters
// (--set ibl.<name>=V, read in GLSL as IBL_<NAME>, uniform block binding 5) and the paper it implements.
// Shader interface (shaders/ibl/*.glsl): vec3 iblRadiance(GlintPixel glint, GlintSurface s, vec3 wo,
// vec3 toEyeWorld, mat3 worldToShading, vec3 diffuseAlbedo, vec3 f0, bool glinty, uint sampleIndex).
// Resources: texture units 16-23, SSBO/UBO bindings 16-23.
// Minimal version written on branch wang (issue 6) following the lead's announced interface; the lead's version
// on main replaces it.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/params.h"
#include "glints/methods.h"

namespace glimmer {

struct IblMode {
    std::string id;
    std::string title;
    std::string define;
    std::string shaderFile;   // relative to shaders/
    std::string citation;
    std::vector<ParamSpec> params;
    bool accumulates = false;  // true: estimates with one sample set per sampleIndex, averaged over --spp frames
    // Optional; created with a current context; update() + bind() run before each lighting pass, after the
    // environment's own bind (units 6-7, block 7).
    std::function<std::unique_ptr<GlintMethodResources>()> createResources;
};

const std::vector<IblMode>& iblModes();
// Throws UsageError("--ibl: unknown mode 'x' (known: ...)").
const IblMode& findIblMode(const std::string& id);
std::string iblParamsGlsl(const IblMode& mode);
std::vector<float> packIblParams(const IblMode& mode, const ParamValues& values);
constexpr int kMaxIblParams = 16;
constexpr unsigned kIblParamBinding = 5;

}  // namespace glimmer
