// The table of glint methods. Each entry names its shader file (shaders/glints/<file>), the define that selects
// it in the lighting program, its parameters (defaults, ranges, meanings) and the paper it implements.
// Adding a method: write shaders/glints/<name>.glsl with the interface documented in shaders/glints/README.md,
// add a function returning its GlintMethod below and list it in glintMethods().
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/params.h"

namespace glimmer {

struct Scene;

// GPU resources a method needs besides its parameters (noise textures, tables). Created once per context when
// the method is selected; bind() runs before every lighting pass. Methods use texture units 8-15 and
// buffer bindings 8-15 (the renderer's own stay below 8).
class GlintMethodResources {
public:
    virtual ~GlintMethodResources() = default;
    // Optional: runs before bind() with the current parameter values of the method/mode, the scene and the
    // environment's source cube (0 when none), so resources that depend on them (IBL sample patterns per material,
    // filtered copies of the environment) can rebuild when they change.
    virtual void prepare(const ParamValues& values, const Scene& scene, unsigned environmentSource) {
        (void)values; (void)scene; (void)environmentSource;
    }
    virtual void bind() = 0;
    // Called before every lighting pass with the method's current parameter values (before bind()): methods
    // whose GPU data depend on parameters rebuild what changed here. Returns the passes that ran (name, wall ms)
    // so the renderer lists them in --stats (material editing, Wang et al. 2020 Sec. 4.5).
    virtual std::vector<std::pair<std::string, double>> update(const ParamValues&) { return {}; }
};

struct GlintMethod {
    std::string id;           // command-line name, e.g. "deliot2023"
    std::string title;        // display name
    std::string define;       // e.g. "GLINT_METHOD_DELIOT2023"
    std::string shaderFile;   // relative to shaders/, e.g. "glints/deliot2023.glsl"
    std::string citation;     // paper reference
    std::vector<ParamSpec> params;  // read in GLSL as P_<NAME> (upper case)
    // Optional: creates the method's GPU resources (called with a current context).
    std::function<std::unique_ptr<GlintMethodResources>()> createResources;
    // Optional screen-space post pass (Wang et al. 2020, Sec. 4.4 "Gaussian Blurring"): the lighting pass writes
    // the method's glint radiance and its directional occlusion to separate targets (lighting.frag,
    // GLINT_POST_PASS); the renderer blurs the occlusion with a Gaussian of `blur_occlusion` taps, multiplies,
    // blurs the glints with one of `blur_glints` taps and adds them (shaders/post/). Such a method declares both
    // parameters.
    bool glintPostPass = false;
};

const std::vector<GlintMethod>& glintMethods();
// Throws UsageError("--method: unknown method 'x' (known: ...)").
const GlintMethod& findGlintMethod(const std::string& id);

// GLSL preamble declaring the method-parameter block and one P_<NAME> macro per parameter.
std::string methodParamsGlsl(const GlintMethod& method);
// Packs values in the order of methodParamsGlsl (std140 vec4 array).
std::vector<float> packMethodParams(const GlintMethod& method, const ParamValues& values);

constexpr int kMaxMethodParams = 64;

// Shared by the method and IBL-mode tables: a std140 block `blockName { vec4 arrayName[capacity / 4]; }` at
// `binding` with one `<macroPrefix><NAME>` macro per parameter, and the matching packing.
std::string parameterBlockGlsl(const std::vector<ParamSpec>& params, unsigned binding, const std::string& blockName,
                               const std::string& arrayName, const std::string& macroPrefix, int capacity);
std::vector<float> packParameters(const std::vector<ParamSpec>& params, const ParamValues& values, int capacity);

}  // namespace glimmer
