#include "render/frame/gbuffer_pass.h"

#include "gl/pipeline_state.h"

namespace glimmer {

GBufferPass::GBufferPass(const std::filesystem::path& shaderRoot)
    : program_(shaderRoot, {"gbuffer", {{GL_VERTEX_SHADER, "frame/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "frame/gbuffer.frag"}}}) {}

void GBufferPass::execute(const FrameContext& frame) {
    gl::PipelineState state = gl::fullscreenState(frame.targets.gbufferFramebuffer(), frame.width, frame.height);
    state.depthTest = true;
    state.depthFunc = GL_GREATER;
    state.depthWrite = true;
    state.apply();
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < FrameTargets::kGBufferColorCount; ++i)
        glClearNamedFramebufferfv(frame.targets.gbufferFramebuffer(), GL_COLOR, i, zero);
    const float clearDepth = 0.0f;
    glClearNamedFramebufferfv(frame.targets.gbufferFramebuffer(), GL_DEPTH, 0, &clearDepth);
    program_.use();
    // GpuScene culls frustum chunks and, on single-sided materials, back faces (it sets and resets the cull state),
    // and draws each chunk at the level of detail lod.pixel_error allows at this frame's (render) size.
    frame.gpuScene.drawInstances(frame.scene, frame.viewProjection, DrawSelection::Opaque, geometryLod(frame));
}

}  // namespace glimmer
