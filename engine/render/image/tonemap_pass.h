// Tone-mapping pass: HDR radiance (or the debug view) -> the display image, sRGB 8-bit (shaders/image/tonemap.frag),
// at the post size. Reads the post HDR radiance, and the bloom result and the exposure state when those passes
// published them this frame; owns and writes FrameResource::Display.
#pragma once
#include <filesystem>

#include "gl/handles.h"
#include "render/frame/pass.h"

namespace glimmer {

class TonemapPass : public Pass {
public:
    explicit TonemapPass(const std::filesystem::path& shaderRoot);
    const char* name() const override { return "tonemap"; }
    PassResources resources() const override {
        return {.reads = {FrameResource::PostHdr, FrameResource::Bloom, FrameResource::ExposureState},
                .writes = {FrameResource::Display}};
    }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    // (Re)allocates the display image at this frame's post size.
    void prepare(PrepareContext& context) override;
    void execute(const FrameContext& frame) override;
    GLuint displayFramebuffer() const { return framebuffer_.id(); }

private:
    gl::Program program_;
    gl::Texture display_;
    gl::Framebuffer framebuffer_;
    gl::Buffer noExposure_;
    int width_ = 0, height_ = 0;
};

}  // namespace glimmer
