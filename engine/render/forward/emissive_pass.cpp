#include "render/forward/emissive_pass.h"

#include "gl/pipeline_state.h"

namespace glimmer {

EmissivePass::EmissivePass(const std::filesystem::path& shaderRoot, std::shared_ptr<ForwardTarget> target)
    : shaderRoot_(shaderRoot), target_(std::move(target)) {}

std::vector<gl::Program*> EmissivePass::programs() {
    if (!program_) return {};
    return {program_.get()};
}

gl::Program& EmissivePass::program() {
    if (!program_)
        program_ = std::make_unique<gl::Program>(
            shaderRoot_, gl::ProgramDesc{"emissive", {{GL_VERTEX_SHADER, "frame/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "forward/forward.frag"}}, {"FORWARD_EMISSIVE"}});
    return *program_;
}

bool EmissivePass::runs(const FrameContext& frame) const {
    return forwardPassesRun(frame) && frame.gpuScene.hasOpaqueEmissive();
}

void EmissivePass::execute(const FrameContext& frame) {
    gl::PipelineState state = gl::fullscreenState(
        target_->framebuffer(frame.resources.write(FrameResource::Hdr), frame.resources.read(FrameResource::Depth)),
        frame.width, frame.height);
    state.depthTest = true;
    state.depthFunc = GL_GEQUAL;   // the G-buffer's own surface (same vertex shader) passes, hidden ones do not
    state.depthWrite = false;
    state.blend = {true, -1, GL_ONE, GL_ONE, GL_ZERO, GL_ONE};   // radiance adds; alpha (coverage) stays
    state.apply();
    program().use();
    // The G-buffer's levels of detail, so that GL_GEQUAL finds the same surfaces.
    frame.gpuScene.drawInstances(frame.scene, frame.viewProjection, DrawSelection::OpaqueEmissive, geometryLod(frame));
}

}  // namespace glimmer
