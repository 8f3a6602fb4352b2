// The table of glint methods. Each entry names its shader file (shaders/glints/<file>), the define that selects
// it in the lighting program, its parameters (defaults, ranges, meanings) and the paper it implements.
// Adding a built-in method: write shaders/glints/<name>.glsl with the interface documented in
// shaders/glints/README.md, add a function returning its GlintMethod below and list it in glintMethods().
// User methods (--method-file, glints/user/user_methods.h) are entries of the same table read from one GLSL file's
// header block at run time: everything that lists or finds methods sees them like the built-ins.
#pragma once
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/params.h"
#include "gl/program.h"
#include "glints/glint_mapping.h"

namespace glimmer {

// GPU resources a method needs besides its parameters (noise textures, tables). Created once per context when
// the method is selected; bind() runs before every lighting pass. Methods use the texture units and buffer
// bindings UNIT_/BINDING_METHOD_FIRST..LAST of shaders/common/bindings.glsl (the renderer's own stay below).
class GlintMethodResources {
public:
    virtual ~GlintMethodResources() = default;
    virtual void bind() = 0;
    // Called before every lighting pass with the method's current parameter values (before bind()): methods
    // whose GPU data depend on parameters rebuild what changed here. Returns the passes that ran (name, wall ms)
    // so the renderer lists them in --stats (material editing, Wang et al. 2020 Sec. 4.5).
    virtual std::vector<std::pair<std::string, double>> update(const ParamValues&) { return {}; }
    // Called before update() with every material's parameter values (glint_mapping.h materialParams; empty for a
    // material that is not glinty): methods whose GPU data depend on per-material values keep them for update()
    // (wang2020: one DPF table per distinct roughness).
    virtual void setMaterials(const std::vector<ParamValues>&) {}
};

// What a method's screen-space pass reads and writes in one frame (see MethodPass).
struct MethodPassFrame {
    int width = 0, height = 0;
    const ParamValues* values = nullptr;   // the method's current parameter values
    int debugView = 0;                     // AovInfo::viewId; 0 = the final image
    // Weight of this frame's radiance in the HDR mean: 1, or 1 / (k + 1) for sample k of an accumulating IBL mode.
    float blendWeight = 1.0f;
    unsigned hdrFramebuffer = 0;           // the HDR radiance target, where the pass adds its result
    // The method's lighting targets (GlintMethod::lightingTargets, in that order) as the lighting pass wrote them.
    std::vector<unsigned> lightingTargets;
    unsigned depth = 0;                    // the G-buffer's depth (reversed Z)
    unsigned emptyVao = 0;                 // bound for full-screen triangles
};

// A pass a method adds after the lighting pass (Wang et al. 2020's Sec. 4.4 post pass is the first). The renderer
// runs a method's passes in order, each in its own debug group and timer named name(); a pass owns its programs
// and intermediate targets and sets its complete pipeline state (gl/pipeline_state.h) before drawing.
class MethodPass {
public:
    virtual ~MethodPass() = default;
    virtual const char* name() const = 0;
    virtual std::vector<gl::Program*> programs() = 0;   // for hot reload and dependency listing
    virtual bool runs(const MethodPassFrame& frame) const { return true; }
    virtual void execute(const MethodPassFrame& frame) = 0;
};
using MethodPassList = std::vector<std::unique_ptr<MethodPass>>;

// A target the lighting pass writes for the method (GlintMethod::lightingTargets): its name (debug label) and
// internal format, at the render size.
struct MethodTarget {
    std::string name;
    GLenum format = GL_RGBA32F;
};

struct GlintMethod {
    std::string id;           // command-line name, e.g. "deliot2023"
    std::string title;        // display name
    std::string define;       // e.g. "GLINT_METHOD_DELIOT2023"
    std::string shaderFile;   // relative to shaders/, e.g. "glints/deliot2023/deliot2023.glsl"
    std::string citation;     // paper reference
    std::vector<ParamSpec> params;  // read in GLSL as P_<NAME> (upper case)
    // Optional: creates the method's GPU resources (called with a current context).
    std::function<std::unique_ptr<GlintMethodResources>()> createResources;
    // Optional: the method's passes after the lighting pass (built with a current context from the shader root;
    // throws gl::ShaderError like any program build).
    std::function<MethodPassList(const std::filesystem::path& shaderRoot)> createPasses;
    // Targets the lighting pass writes for the method besides the radiance, at locations 2.. in this order, which
    // its passes read (MethodPassFrame::lightingTargets). The method's shader then declares those outputs and the
    // hooks of shaders/glints/README.md ("Lighting targets"; the lighting program is compiled with
    // GLINT_METHOD_TARGETS): wang2020 keeps its glint radiance and directional occlusion out of the radiance so that
    // its Sec. 4.4 passes can blur them and add them. At most 6 (8 draw buffers).
    std::vector<MethodTarget> lightingTargets;
    // The lighting pass fills GlintSurface's screen-space derivatives of the position and the shading normal and
    // sets g_glintLightDistance per light (GLINT_SURFACE_DERIVATIVES; shaders/common/glint_surface.glsl), for
    // methods that filter over the pixel's range of half vectors (Chermain et al. 2021's anti-aliasing).
    bool surfaceDerivatives = false;
    // The G-buffer pass filters normal maps by LEAN mapping (Olano & Baker 2010) and writes the filtered slope
    // covariance, which the lighting pass hands to the method (GlintSurface::slopeCovariance, GLINT_SLOPE_COVARIANCE;
    // texture unit UNIT_GBUFFER_SLOPE_COVARIANCE must stay free of the method's resources).
    bool slopeCovariance = false;
    // The method draws glints from the environment (its shader defines GLINT_ENVIRONMENT; Kneiphof & Klein 2025):
    // the renderer builds the environment's radiance levels for it (environment/environment_glints.h).
    bool environmentGlints = false;
    // The IBL mode the method uses unless --ibl (or the panel) names one: a method with environment glints of its
    // own (wang2020) draws them by default. Empty: "prefiltered".
    std::string defaultIbl;
    // How the glint material (scene.h GlintMaterial) sets this method's parameters per material (glint_mapping.h);
    // parameters without a mapping keep their default unless --set. Each row cites the paper's definition.
    std::vector<ParamMapping> materialMapping;
    // The method's shared GPU data (createResources' update()) are built from one material's values: the glinty
    // material with the largest value of this parameter (wang2020: particles, so that every material thins the
    // densest material's tree), or the first glinty material when empty. Shaders read those values as PS_<NAME>.
    std::string sharedDataMaterial;
    // Parameter values at which the method must render like `smooth` ("very high density"): the convergence
    // rule of check-method (checks/method_checks.h). Empty: the method declares none.
    ParamValues convergence;
    // User methods only: the GLSL file the entry was read from (canonical; shaderFile is the same path) and the
    // built-in whose GPU resources it borrows ("" = none). Built-ins leave both empty.
    std::filesystem::path sourceFile;
    std::string resourcesFrom;
    bool isUserMethod() const { return !sourceFile.empty(); }
};

// The IBL mode `method` runs with unless one is named: its defaultIbl, else "prefiltered".
inline std::string defaultIblOf(const GlintMethod& method) {
    return method.defaultIbl.empty() ? std::string("prefiltered") : method.defaultIbl;
}

// The built-ins, then the user methods in the order they were registered. References stay valid only until the
// next registerGlintMethod (look methods up again after loading a method file).
const std::vector<GlintMethod>& glintMethods();
// Throws UsageError("--method: unknown method 'x' (known: ...)").
const GlintMethod& findGlintMethod(const std::string& id);
// Adds a user method, or replaces the entry read from the same file (hot reload of its header, which may rename
// it). Returns the id the file's entry had before ("" for a new file). Throws Error when the id is a built-in's
// or another file's.
std::string registerGlintMethod(GlintMethod method);

// GLSL preamble declaring the method-parameter block and one P_<NAME> macro per parameter. With perMaterial
// (the lighting pass), P_<NAME> reads the row of the material g_glintMaterial in a storage buffer
// (BINDING_MATERIAL_METHOD_PARAMS, kMaxMethodParams floats per material, packMethodParams order) and the block
// holds the shared values (PS_<NAME>); otherwise P_<NAME> and PS_<NAME> both read the block. A parameter in
// `constants` makes P_<NAME> that constant instead (the lighting pass's enumerations that every material shares:
// uniformChoices).
std::string methodParamsGlsl(const GlintMethod& method, bool perMaterial = false, const ParamValues& constants = {});
// The method's enumerations (ParamSpec::choices) that have one value on every row of `perMaterial` (each material's
// values, glint_mapping.h materialParams), with that value; none when `perMaterial` is empty. The lighting program
// compiles them as constants: llvmpipe runs both sides of every branch, so a per-material switch between two
// variants of a method paid for both at every glinty pixel (kemppinen2025's 4 or 16 neighbours: 20 cells).
ParamValues uniformChoices(const GlintMethod& method, const std::vector<ParamValues>& perMaterial);
// Packs values in the order of methodParamsGlsl (std140 vec4 array).
std::vector<float> packMethodParams(const GlintMethod& method, const ParamValues& values);

constexpr int kMaxMethodParams = 64;

// Shared by the method and IBL-mode tables: a std140 block `blockName { vec4 arrayName[capacity / 4]; }` at
// `binding` with one `<macroPrefix><NAME>` macro per parameter, and the matching packing.
std::string parameterBlockGlsl(const std::vector<ParamSpec>& params, unsigned binding, const std::string& blockName,
                               const std::string& arrayName, const std::string& macroPrefix, int capacity);
std::vector<float> packParameters(const std::vector<ParamSpec>& params, const ParamValues& values, int capacity);

}  // namespace glimmer
