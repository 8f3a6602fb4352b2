// Lighting pass: one full-screen triangle reading the G-buffer, the environment and the resources of the glint
// method and the IBL mode (shaders/frame/lighting.frag), writing linear HDR radiance. A method with a glint post pass
// (GlintMethod::glintPostPass) also writes its glint targets (FrameTargets::lightingGlintFramebuffer()); with TAA it
// also writes the glint part (FrameTargets::glintPartTexture(), attachment 3). Later
// samples of an accumulated view blend into the running mean (draw buffer 0 only).
// Shading classes (lighting.split_glinty=1, the window's default): llvmpipe executes both sides of a branch, so
// one shader made every pixel pay for the method's light loop whether its material was glinty or not. Split,
// the pass first writes each pixel's class into FrameTargets' shading-class depth (shaders/frame/lighting_class.frag:
// 1 glinty, 0 not), then draws the method's program at depth 1 and the program compiled with NON_GLINTY_PIXELS
// (glinty = false: no method code) at depth 0, each with an early GL_EQUAL depth test, so each pixel is shaded
// once by the program of its class. Non-glinty pixels get the same terms either way (tested). Debug views (AOVs)
// are not split.
#pragma once
#include <filesystem>
#include <memory>

#include "render/frame/pass.h"

namespace glimmer {

// The lighting program of a method and an IBL mode (defines, generated parameter blocks, included files).
// `shadows`: compiled with the shadow lookups (SHADOWS); without, every light's visibility is the constant 1, so
// shadow.enabled=0 runs today's shader (llvmpipe executes both sides of a branch: a runtime switch would not).
// `nonGlinty`: the variant for the pixels of non-glinty materials (NON_GLINTY_PIXELS).
gl::ProgramDesc lightingProgramDesc(const std::string& methodId, const std::string& iblId, bool shadows = true,
                                    bool nonGlinty = false);

class LightingPass : public Pass {
public:
    LightingPass(const std::filesystem::path& shaderRoot, const std::string& methodId, const std::string& iblId,
                 bool shadows);
    bool shadows() const { return shadows_; }
    const char* name() const override { return "lighting"; }
    std::vector<gl::Program*> programs() override;
    void execute(const FrameContext& frame) override;

private:
    // Built on the first split frame (offscreen renders that never split do not compile them).
    void buildSplitPrograms();
    // Textures, buffers and resources both programs read (uniform state of the method / IBL mode included).
    void bindInputs(const FrameContext& frame);
    std::filesystem::path shaderRoot_;
    std::string methodId_, iblId_;
    gl::Program program_;
    std::unique_ptr<gl::Program> nonGlintyProgram_, classProgram_;
    gl::Texture unoccluded_;   // 1 x 1 white: frames without an AO texture (probe captures) are not occluded
    bool shadows_;
};

}  // namespace glimmer
