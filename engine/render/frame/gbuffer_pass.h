// G-buffer pass: every opaque instance into the G-buffer (layout in shaders/frame/gbuffer.frag) and its depth.
// Reversed Z (cleared to 0, GREATER passes), no blending, back faces of single-sided materials culled (GpuScene).
// Owns both targets (FrameResource::GBuffer, Depth) at the render size. Skipped on later samples of an accumulated
// view, which reuse sample 0's G-buffer. For glint methods that filter normal maps (GlintMethod::slopeCovariance)
// it runs the GBUFFER_SLOPE_COVARIANCE program: normal maps through their LEAN maps (GpuScene::ensureLeanMaps) and
// the filtered slope covariance into a seventh target, published as the G-buffer's texture 6.
#pragma once
#include <filesystem>
#include <memory>

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
    std::vector<gl::Program*> programs() override;
    void resize(const View& view, FrameResources& resources) override;
    void prepare(PrepareContext& context) override;
    bool runs(const FrameContext& frame) const override { return !frame.blendSample; }
    void execute(const FrameContext& frame) override;

private:
    void publish(FrameResources& resources) const;
    std::filesystem::path shaderRoot_;
    // The programs' variant: with the lookups of the occlusion, glint-mask and clear-coat textures
    // (GBUFFER_EXTRA_TEXTURES) only while a material of the scene has one; llvmpipe samples a texture under an
    // all-off mask, which cost the atrium 2.5-4 ms of a 20 ms pass for slots none of its materials use.
    bool extraTextures_ = false;
    gl::Program program_;
    std::unique_ptr<gl::Program> slopeProgram_;   // built on first use
    gl::Texture colors_[kColorCount], depth_;
    gl::Framebuffer framebuffer_;
    int width_ = 0, height_ = 0;
    bool slopeCovariance_ = false;                 // this frame's method reads target 6
    gl::Texture slopeTarget_;                      // target 6, allocated on first use at the render size
    gl::Framebuffer slopeFramebuffer_;
};

}  // namespace glimmer
