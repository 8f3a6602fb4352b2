// Lighting pass: one full-screen triangle reading the G-buffer, the environment and the resources of the glint
// method and the IBL mode (shaders/lighting.frag), writing linear HDR radiance. A method with a glint post pass
// (GlintMethod::glintPostPass) also writes its glint targets (FrameTargets::lightingGlintFramebuffer()); with TAA it
// also writes the glint part (FrameTargets::glintPartTexture(), attachment 3). Later
// samples of an accumulated view blend into the running mean (draw buffer 0 only).
#pragma once
#include <filesystem>

#include "render/passes/pass.h"

namespace glimmer {

// The lighting program of a method and an IBL mode (defines, generated parameter blocks, included files).
gl::ProgramDesc lightingProgramDesc(const std::string& methodId, const std::string& iblId);

class LightingPass : public Pass {
public:
    LightingPass(const std::filesystem::path& shaderRoot, const std::string& methodId, const std::string& iblId);
    const char* name() const override { return "lighting"; }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    void execute(const FrameContext& frame) override;

private:
    gl::Program program_;
    gl::Texture unoccluded_;   // 1 x 1 white: frames without an AO texture (probe captures) are not occluded
};

}  // namespace glimmer
