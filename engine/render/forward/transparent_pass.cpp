#include "render/forward/transparent_pass.h"

#include "gl/pipeline_state.h"

namespace glimmer {

TransparentPass::TransparentPass(const std::filesystem::path& shaderRoot, std::shared_ptr<ForwardTarget> target)
    : shaderRoot_(shaderRoot), target_(std::move(target)) {}

std::vector<gl::Program*> TransparentPass::programs() {
    if (!program_) return {};
    return {program_.get()};
}

gl::Program& TransparentPass::program() {
    if (!program_)
        program_ = std::make_unique<gl::Program>(
            shaderRoot_, gl::ProgramDesc{"transparent", {{GL_VERTEX_SHADER, "frame/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "forward/forward.frag"}}, {"FORWARD_TRANSPARENT"}});
    return *program_;
}

bool TransparentPass::runs(const FrameContext& frame) const {
    return forwardPassesRun(frame) && frame.gpuScene.hasBlended();
}

void TransparentPass::execute(const FrameContext& frame) {
    gl::PipelineState state = gl::fullscreenState(
        target_->framebuffer(frame.resources.write(FrameResource::Hdr), frame.resources.read(FrameResource::Depth)),
        frame.width, frame.height);
    state.depthTest = true;
    state.depthFunc = GL_GREATER;   // reversed Z: in front of the opaque surface
    state.depthWrite = false;
    // "over": rgb = a * src + (1 - a) * dst; the target's alpha (unused by tone mapping) is left alone.
    state.blend = {true, -1, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE};
    state.apply();
    program().use();
    frame.environment.bind(frame.settings.value(param::env_intensity), frame.settings.value(param::env_rotation));
    frame.gpuScene.drawBlendedBackToFront(frame.scene, frame.viewProjection, frame.camera.position);
}

}  // namespace glimmer
