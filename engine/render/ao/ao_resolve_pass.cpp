#include "render/ao/ao_resolve_pass.h"

#include <glm/gtc/type_ptr.hpp>

#include "common/bindings.glsl"
#include "gl/pipeline_state.h"

namespace glimmer {

AoResolvePass::AoResolvePass(const std::filesystem::path& shaderRoot, const AmbientOcclusion& ao)
    : program_(shaderRoot,
               {"ao_resolve", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "ao/ao_resolve.frag"}}}),
      ao_(ao) {}

void AoResolvePass::execute(const FrameContext& frame) {
    gl::fullscreenState(ao_.resolveFramebuffer(), ao_.targetWidth(), ao_.targetHeight()).apply();
    program_.use();
    const AoSettings& s = ao_.settings();
    glProgramUniform4f(program_.id(), 0, s.screen ? 1.0f : 0.0f, s.denoise ? 1.0f : 0.0f, s.power,
                       s.multiBounce ? 1.0f : 0.0f);
    const glm::mat4 inverseProjection = glm::inverse(frame.camera.projection(float(frame.width) / float(frame.height)));
    glProgramUniformMatrix4fv(program_.id(), 1, 1, GL_FALSE, glm::value_ptr(inverseProjection));
    glProgramUniform1i(program_.id(), 5, ao_.step());
    auto gbuffer = [&](int unit) { return frame.targets.gbufferTexture(unit - UNIT_GBUFFER_FIRST); };
    glBindTextureUnit(UNIT_AO_DEPTH, frame.targets.depthTexture());
    glBindTextureUnit(UNIT_AO_NORMAL, gbuffer(UNIT_GBUFFER_NORMAL_ALPHA));
    glBindTextureUnit(UNIT_AO_RAW, ao_.rawTexture());
    glBindTextureUnit(UNIT_AO_BASE_COLOR, gbuffer(UNIT_GBUFFER_BASE_COLOR_MASK));
    glBindTextureUnit(UNIT_AO_TANGENT_METALLIC, gbuffer(UNIT_GBUFFER_TANGENT_METALLIC));
    ao_.bindSky(program_.id());
    glBindVertexArray(frame.emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace glimmer
