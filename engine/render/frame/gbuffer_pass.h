// G-buffer pass: every instance into the G-buffer (layout in shaders/frame/gbuffer.frag) and its depth. Reversed Z
// (cleared to 0, GREATER passes), no blending, no culling (glTF double-sided surfaces). Skipped on later samples
// of an accumulated view, which reuse sample 0's G-buffer.
#pragma once
#include <filesystem>

#include "render/frame/pass.h"

namespace glimmer {

class GBufferPass : public Pass {
public:
    explicit GBufferPass(const std::filesystem::path& shaderRoot);
    const char* name() const override { return "gbuffer"; }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    bool runs(const FrameContext& frame) const override { return !frame.blendSample; }
    void execute(const FrameContext& frame) override;

private:
    gl::Program program_;
};

}  // namespace glimmer
