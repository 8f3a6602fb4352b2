// Tone-mapping pass: HDR radiance (or the debug view) -> the display image, sRGB 8-bit (shaders/image/tonemap.frag).
// Reads the HDR target, the bloom pass's result and the exposure pass's state when those ran this frame.
#pragma once
#include <filesystem>

#include "render/image/bloom_pass.h"
#include "render/image/exposure_pass.h"
#include "render/frame/pass.h"

namespace glimmer {

class TonemapPass : public Pass {
public:
    TonemapPass(const std::filesystem::path& shaderRoot, const BloomPass& bloom, const ExposurePass& exposure);
    const char* name() const override { return "tonemap"; }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    void execute(const FrameContext& frame) override;

private:
    gl::Program program_;
    const BloomPass& bloom_;
    const ExposurePass& exposure_;
};

}  // namespace glimmer
