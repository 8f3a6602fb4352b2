#include "render/passes/gbuffer_pass.h"

#include "gl/pipeline_state.h"
#include "glints/methods.h"

namespace glimmer {

GBufferPass::GBufferPass(const std::filesystem::path& shaderRoot)
    : shaderRoot_(shaderRoot),
      program_(shaderRoot, {"gbuffer", {{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "gbuffer.frag"}}}) {}

std::vector<gl::Program*> GBufferPass::programs() {
    std::vector<gl::Program*> all{&program_};
    if (slopeProgram_) all.push_back(slopeProgram_.get());
    return all;
}

void GBufferPass::execute(const FrameContext& frame) {
    const bool slopeCovariance = findGlintMethod(frame.settings.method).slopeCovariance;
    if (slopeCovariance && !slopeProgram_) {
        gl::ProgramDesc desc{"gbuffer/slope covariance",
                             {{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "gbuffer.frag"}}};
        desc.defines = {"GBUFFER_SLOPE_COVARIANCE"};
        slopeProgram_ = std::make_unique<gl::Program>(shaderRoot_, desc);
    }
    if (slopeCovariance) frame.gpuScene.ensureLeanMaps(frame.scene);
    const GLuint fbo = slopeCovariance ? frame.targets.gbufferSlopeFramebuffer() : frame.targets.gbufferFramebuffer();
    gl::PipelineState state = gl::fullscreenState(fbo, frame.width, frame.height);
    state.depthTest = true;
    state.depthFunc = GL_GREATER;
    state.depthWrite = true;
    state.apply();
    const float zero[4] = {0, 0, 0, 0};
    const int targets = FrameTargets::kGBufferColorCount + (slopeCovariance ? 1 : 0);
    for (int i = 0; i < targets; ++i) glClearNamedFramebufferfv(fbo, GL_COLOR, i, zero);
    const float clearDepth = 0.0f;
    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &clearDepth);
    (slopeCovariance ? *slopeProgram_ : program_).use();
    // GpuScene culls frustum chunks and, on single-sided materials, back faces (it sets and resets the cull state),
    // and draws each chunk at the level of detail lod.pixel_error allows at this frame's (render) size.
    frame.gpuScene.drawInstances(frame.scene, frame.viewProjection, DrawSelection::Opaque, geometryLod(frame));
}

}  // namespace glimmer
