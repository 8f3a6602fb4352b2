#include "render/ao/ao_resolve_pass.h"

#include <glm/gtc/type_ptr.hpp>

#include "common/bindings.glsl"
#include "gl/pipeline_state.h"

namespace glimmer {

AoResolvePass::AoResolvePass(const std::filesystem::path& shaderRoot, std::shared_ptr<AmbientOcclusion> ao)
    : program_(shaderRoot,
               {"ao_resolve", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "ao/ao_resolve.frag"}}}),
      ao_(std::move(ao)) {}

void AoResolvePass::prepare(PrepareContext& context) {
    const bool on = ao_->settings().enabled;
    context.resources.publish(FrameResource::AmbientOcclusion,
                              {.textures = {ao_->occlusionTexture()},
                               .width = on ? ao_->targetWidth() : 1,
                               .height = on ? ao_->targetHeight() : 1});
}

void AoResolvePass::execute(const FrameContext& frame) {
    const FrameImage& gbufferImage = frame.resources.read(FrameResource::GBuffer);
    const GLuint depth = frame.resources.read(FrameResource::Depth).texture();
    const GLuint raw = frame.resources.read(FrameResource::AmbientOcclusionRaw).texture();
    frame.resources.write(FrameResource::AmbientOcclusion);
    gl::fullscreenState(ao_->resolveFramebuffer(), ao_->targetWidth(), ao_->targetHeight()).apply();
    program_.use();
    const AoSettings& s = ao_->settings();
    glProgramUniform4f(program_.id(), 0, s.screen ? 1.0f : 0.0f, s.denoise ? 1.0f : 0.0f, s.power,
                       s.multiBounce ? 1.0f : 0.0f);
    const glm::mat4 inverseProjection = glm::inverse(frame.camera.projection(float(frame.width) / float(frame.height)));
    glProgramUniformMatrix4fv(program_.id(), 1, 1, GL_FALSE, glm::value_ptr(inverseProjection));
    glProgramUniform1i(program_.id(), 5, ao_->step());
    auto gbuffer = [&](int unit) { return gbufferImage.texture(size_t(unit - UNIT_GBUFFER_FIRST)); };
    glBindTextureUnit(UNIT_AO_DEPTH, depth);
    glBindTextureUnit(UNIT_AO_NORMAL, gbuffer(UNIT_GBUFFER_NORMAL_ALPHA));
    glBindTextureUnit(UNIT_AO_RAW, raw);
    glBindTextureUnit(UNIT_AO_BASE_COLOR, gbuffer(UNIT_GBUFFER_BASE_COLOR_MASK));
    glBindTextureUnit(UNIT_AO_TANGENT_METALLIC, gbuffer(UNIT_GBUFFER_TANGENT_METALLIC));
    ao_->bindSky(program_.id());
    glBindVertexArray(frame.emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace glimmer
