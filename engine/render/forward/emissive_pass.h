// Emissive pass: adds the emitted radiance of opaque and masked emissive materials (glTF emissiveFactor x
// KHR_materials_emissive_strength x emissiveTexture) to the HDR radiance after lighting. It draws those
// instances again with the G-buffer's vertex shader, depth-tested GEQUAL against the G-buffer depth (reversed Z,
// no writes) so only the visible surface adds, additive blending. Blended materials emit in the transparent pass.
#pragma once
#include <filesystem>
#include <memory>

#include "render/forward/forward_target.h"

namespace glimmer {

class EmissivePass : public Pass {
public:
    EmissivePass(const std::filesystem::path& shaderRoot, std::shared_ptr<ForwardTarget> target);
    const char* name() const override { return "emissive"; }
    PassResources resources() const override { return {.reads = {FrameResource::Depth}, .writes = {FrameResource::Hdr}}; }
    // The program is built on the first frame that needs it: most scenes never do, and every build costs.
    std::vector<gl::Program*> programs() override;
    bool runs(const FrameContext& frame) const override;
    void execute(const FrameContext& frame) override;

private:
    gl::Program& program();
    std::filesystem::path shaderRoot_;
    std::unique_ptr<gl::Program> program_;
    std::shared_ptr<ForwardTarget> target_;
};

}  // namespace glimmer
