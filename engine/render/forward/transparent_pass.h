// Transparent pass: glTF alphaMode BLEND materials (3.9.4), after lighting and the method passes, before tone
// mapping. Their instances are not in the G-buffer; here each visible chunk is drawn forward-shaded
// (shaders/forward/forward.frag: the same Cook-Torrance + Lambert model and lights as the lighting pass, the prefiltered
// environment, emission, no glints), sorted back to front by chunk centre, and composited "over" the HDR radiance:
// C = a * S + (1 - a) * C_behind with a = baseColor.a x texture alpha x COLOR_0 alpha. Depth-tested against the
// opaque depth, no depth writes; single-sided materials cull back faces (mirrored nodes flip the winding).
#pragma once
#include <filesystem>
#include <memory>

#include "render/forward/forward_target.h"

namespace glimmer {

class TransparentPass : public Pass {
public:
    TransparentPass(const std::filesystem::path& shaderRoot, std::shared_ptr<ForwardTarget> target);
    const char* name() const override { return "transparent"; }
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
