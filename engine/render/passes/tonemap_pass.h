// Tone-mapping pass: HDR radiance (or the debug view) -> the display image, sRGB 8-bit (shaders/tonemap.frag).
#pragma once
#include <filesystem>

#include "render/passes/pass.h"

namespace glimmer {

class TonemapPass : public Pass {
public:
    explicit TonemapPass(const std::filesystem::path& shaderRoot);
    const char* name() const override { return "tonemap"; }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    void execute(const FrameContext& frame) override;

private:
    gl::Program program_;
};

}  // namespace glimmer
