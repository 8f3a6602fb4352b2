#include "render/ao/gtao_pass.h"

#include <glm/gtc/type_ptr.hpp>

#include "common/bindings.glsl"
#include "gl/pipeline_state.h"
#include "gl/samplers.h"
#include "render/frame/pass_timer.h"

namespace glimmer {

GtaoPass::GtaoPass(const std::filesystem::path& shaderRoot, std::shared_ptr<AmbientOcclusion> ao)
    : program_(shaderRoot, {"gtao", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "ao/gtao.frag"}}}),
      ao_(std::move(ao)) {
    linearDepthSampler_ = gl::createLinearClampSampler();
}

GtaoPass::~GtaoPass() = default;

void GtaoPass::prepare(PrepareContext& context) {
    // Sky visibility of a new scene (baked or loaded from the cache) before any pass of this frame.
    for (const PassTiming& ran : ao_->prepare(context.settings, context.scene, context.gpuScene.serial(),
                                              context.view.width, context.view.height))
        context.recordStats(ran.name, ran.wallMs);
    context.resources.publish(FrameResource::AmbientOcclusionRaw,
                              {.textures = {ao_->rawTexture()}, .width = ao_->targetWidth(), .height = ao_->targetHeight()});
}

bool GtaoPass::runs(const FrameContext& frame) const {
    return ao_->settings().enabled && ao_->settings().screen && !frame.blendSample;
}

void GtaoPass::execute(const FrameContext& frame) {
    const FrameImage& gbuffer = frame.resources.read(FrameResource::GBuffer);
    const GLuint depth = frame.resources.read(FrameResource::Depth).texture();
    frame.resources.write(FrameResource::AmbientOcclusionRaw);
    gl::fullscreenState(ao_->rawFramebuffer(), ao_->targetWidth(), ao_->targetHeight()).apply();
    program_.use();
    const AoSettings& s = ao_->settings();
    const glm::mat4 inverseProjection = glm::inverse(frame.camera.projection(float(frame.width) / float(frame.height)));
    glProgramUniformMatrix4fv(program_.id(), 0, 1, GL_FALSE, glm::value_ptr(inverseProjection));
    glProgramUniform4f(program_.id(), 1, s.radius, float(s.slices), float(s.steps), s.falloff);
    glProgramUniform1i(program_.id(), 2, ao_->step());
    glBindTextureUnit(UNIT_AO_DEPTH, depth);
    glBindTextureUnit(UNIT_AO_NORMAL, gbuffer.texture(UNIT_GBUFFER_NORMAL_ALPHA - UNIT_GBUFFER_FIRST));
    glBindSampler(UNIT_AO_DEPTH, linearDepthSampler_.id());
    glBindVertexArray(frame.emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindSampler(UNIT_AO_DEPTH, 0);   // later passes read this unit with the texture's own state
}

}  // namespace glimmer
