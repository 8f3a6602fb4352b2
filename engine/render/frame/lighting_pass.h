// Lighting pass: one full-screen triangle reading the G-buffer, the environment, the shadow mask, the ambient
// occlusion, the reflection probes and the resources of the glint method and the IBL mode (shaders/frame/lighting.frag),
// writing linear HDR radiance (FrameResource::Hdr, owned here). A method whose table entry lists lighting targets
// (GlintMethod::lightingTargets: wang2020's glint targets for its Sec. 4.4 post pass) gets them allocated here at
// locations 2.. (FrameResource::MethodTargets); with TAA the pass also writes the glint part (FrameResource::GlintPart,
// location 1, allocated by the TAA pass). Later samples of an accumulated view blend into the running mean (draw
// buffer 0 only).
//
// The pass owns the selected method's and IBL mode's GPU resources and parameter buffers: its prepare() rebuilds
// what an edit changed (the per-material parameters, the method's tables, the IBL mode's per-object maps).
//
// Shading classes (lighting.split_glinty=1, the window's default): llvmpipe executes both sides of a branch, so
// one shader made every pixel pay for the method's light loop whether its material was glinty or not. Split,
// the pass first writes each pixel's class into the shading-class depth (FrameResource::ShadingClass;
// shaders/frame/lighting_class.frag: 1 glinty, 0 not), then draws the method's program at depth 1 and the program
// compiled with NON_GLINTY_PIXELS (glinty = false: no method code) at depth 0, each with an early GL_EQUAL depth
// test, so each pixel is shaded once by the program of its class. Non-glinty pixels get the same terms either way
// (tested). Debug views (AOVs) are not split.
#pragma once
#include <filesystem>
#include <memory>

#include "environment/ibl/scene_capture.h"
#include "gl/handles.h"
#include "render/frame/environment_glints_pass.h"
#include "render/frame/pass.h"
#include "render/lights/ltc_texture.h"

namespace glimmer {

// The lighting program of a method and an IBL mode (defines, generated parameter blocks, included files).
// `shadows`: compiled with the shadow lookups (SHADOWS); without, every light's visibility is the constant 1, so
// shadow.enabled=0 runs today's shader (llvmpipe executes both sides of a branch: a runtime switch would not).
// `nonGlinty`: the variant for the pixels of non-glinty materials (NON_GLINTY_PIXELS).
// `clearcoat`: compiled with the clear coat's terms (SCENE_CLEARCOAT); a scene without a coated material gets the
// program without them (llvmpipe ran them under an all-off mask: 2-6 ms of the atrium's 45 ms lighting pass).
// `constantChoices`: the method's enumerations compiled as constants (methods.h uniformChoices: those every material
// of the scene shares; rebuilt when that changes).
gl::ProgramDesc lightingProgramDesc(const std::string& methodId, const std::string& iblId, bool shadows = true,
                                    bool nonGlinty = false, bool clearcoat = true,
                                    const ParamValues& constantChoices = {});
// Whether any of the scene's materials has a clear coat (the lighting program's `clearcoat` variant).
bool sceneHasClearcoat(const Scene& scene);

class LightingPass : public Pass {
public:
    // `capture` renders the scene for IBL modes with per-object environment maps (kept by the renderer).
    LightingPass(const std::filesystem::path& shaderRoot, const RenderSettings& settings, ibl::SceneCapture& capture);
    ~LightingPass() override;
    const char* name() const override { return "lighting"; }
    PassResources resources() const override;
    std::vector<gl::Program*> programs() override;
    void resize(const View& view, FrameResources& resources) override;
    void prepare(PrepareContext& context) override;
    void execute(const FrameContext& frame) override;

    bool shadows() const { return shadows_; }
    const std::string& methodId() const { return methodId_; }
    // Rebuilds the main program (hot reload: a user method's header may have changed its parameters); a failure
    // throws and keeps the running one. Returns true when the method's resources had to be recreated.
    bool rebuildProgram();
    // shadow.enabled toggled: rebuilds the programs with or without the shadow lookups, keeping the method's data.
    void setShadows(bool shadows);
    GlintMethodResources* methodResources() const { return methodResources_.get(); }

private:
    // This pass's lighting program (the glinty one, or the variant for the other pixels) for its current state.
    gl::ProgramDesc programDesc(bool nonGlinty) const;
    // Rebuilds the lighting program (the split variant on its next frame) after a change of that state.
    void rebuildVariant();
    void createMethodResources();
    // Built on the first split frame (offscreen renders that never split do not compile them).
    void buildSplitPrograms();
    // The method's parameters of every material (glint material mapped, --set overrides on top) and the shared
    // values its GPU data are built from.
    void uploadMethodParams(const Scene& scene, const RenderSettings& settings);
    // Textures, buffers and resources both programs read (uniform state of the method / IBL mode included).
    void bindInputs(const FrameContext& frame);

    std::filesystem::path shaderRoot_;
    std::string methodId_, iblId_;
    bool shadows_;
    bool clearcoat_ = false;   // the programs' variant: built for a scene with coated materials (prepare() follows it)
    ParamValues constantChoices_;   // the enumerations compiled as constants (prepare() follows the materials)
    bool variantChanged_ = false;   // clearcoat_ or constantChoices_ changed: prepare() rebuilds the programs
    ibl::SceneCapture& capture_;
    gl::Program program_;
    std::unique_ptr<gl::Program> nonGlintyProgram_, classProgram_;
    std::unique_ptr<GlintMethodResources> methodResources_;
    std::string methodResourcesFrom_;   // GlintMethod::resourcesFrom of the resources made (user methods may change it)
    std::unique_ptr<IblModeResources> iblResources_;
    gl::Buffer methodParams_, iblParams_;
    LtcTexture ltcTable_;                     // the area lights' LTC tables (unit 32)
    NoEnvironmentGlints noEnvironmentGlints_; // bound when the frame has no environment glints
    gl::Buffer materialMethodParams_;   // per-material method parameters (BINDING_MATERIAL_METHOD_PARAMS)
    long long materialMethodParamsBytes_ = 0;
    ParamValues sharedMethodValues_;    // what the method's shared GPU data are built from (glint_mapping.h)
    gl::Texture hdr_, shadingClass_;
    std::vector<gl::Texture> methodTargets_;
    gl::AttachedFramebuffer classFramebuffer_, framebuffer_;
};

}  // namespace glimmer
