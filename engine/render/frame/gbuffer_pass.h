// G-buffer pass: every opaque instance into the G-buffer (layout in shaders/frame/gbuffer.frag) and its depth.
// Reversed Z (cleared to 0, GREATER passes), no blending, back faces of single-sided materials culled (GpuScene).
// Owns both targets (FrameResource::GBuffer, Depth) at the render size. Skipped on later samples of an accumulated
// view, which reuse sample 0's G-buffer.
#pragma once
#include <filesystem>

#include "gl/handles.h"
#include "render/frame/pass.h"

namespace glimmer {

class GBufferPass : public Pass {
public:
    // Target 5 (KHR_materials_clearcoat) is read by the lighting pass at UNIT_GBUFFER_CLEARCOAT, not at
    // UNIT_GBUFFER_FIRST + 5 (the depth).
    static constexpr int kColorCount = 6;

    explicit GBufferPass(const std::filesystem::path& shaderRoot);
    const char* name() const override { return "gbuffer"; }
    PassResources resources() const override { return {.writes = {FrameResource::GBuffer, FrameResource::Depth}}; }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    void resize(const View& view, FrameResources& resources) override;
    void prepare(PrepareContext& context) override;
    bool runs(const FrameContext& frame) const override { return !frame.blendSample; }
    void execute(const FrameContext& frame) override;

private:
    gl::Program program_;
    gl::Texture colors_[kColorCount], depth_;
    gl::Framebuffer framebuffer_;
};

}  // namespace glimmer
