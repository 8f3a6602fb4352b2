// G-buffer pass: every instance into the G-buffer (layout in shaders/gbuffer.frag) and its depth. Reversed Z
// (cleared to 0, GREATER passes), no blending, no culling (glTF double-sided surfaces). Skipped on later samples
// of an accumulated view, which reuse sample 0's G-buffer. For glint methods that filter normal maps
// (GlintMethod::slopeCovariance) it runs the GBUFFER_SLOPE_COVARIANCE program: normal maps through their LEAN maps
// (GpuScene::ensureLeanMaps) and the filtered slope covariance into target 6.
#pragma once
#include <filesystem>
#include <memory>

#include "render/passes/pass.h"

namespace glimmer {

class GBufferPass : public Pass {
public:
    explicit GBufferPass(const std::filesystem::path& shaderRoot);
    const char* name() const override { return "gbuffer"; }
    std::vector<gl::Program*> programs() override;
    bool runs(const FrameContext& frame) const override { return !frame.blendSample; }
    void execute(const FrameContext& frame) override;

private:
    std::filesystem::path shaderRoot_;
    gl::Program program_;
    std::unique_ptr<gl::Program> slopeProgram_;   // built on first use
};

}  // namespace glimmer
