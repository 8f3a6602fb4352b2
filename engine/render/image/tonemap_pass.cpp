#include "render/image/tonemap_pass.h"

#include "gl/pipeline_state.h"
#include "common/bindings.glsl"

namespace glimmer {

TonemapPass::TonemapPass(const std::filesystem::path& shaderRoot, const BloomPass& bloom, const ExposurePass& exposure)
    : program_(shaderRoot, {"tonemap", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "image/tonemap.frag"}}}),
      bloom_(bloom),
      exposure_(exposure) {}

void TonemapPass::execute(const FrameContext& frame) {
    gl::fullscreenState(frame.targets.displayFramebuffer(), frame.targets.postWidth(), frame.targets.postHeight()).apply();
    program_.use();
    const bool bloom = BloomPass::wanted(frame.settings) && bloom_.result();
    glBindTextureUnit(UNIT_TONEMAP_HDR, frame.targets.postHdrTexture());
    glBindTextureUnit(UNIT_TONEMAP_BLOOM, bloom ? bloom_.result() : frame.targets.postHdrTexture());
    exposure_.bindState();
    glProgramUniform1i(program_.id(), 0, int(frame.settings.common_("tonemap")));
    glProgramUniform1f(program_.id(), 1, bloom ? frame.settings.common_("bloom.strength") : 0.0f);
    glProgramUniform1i(program_.id(), 2, ExposurePass::wanted(frame.settings) ? 1 : 0);
    glProgramUniform1f(program_.id(), 3, bloom_.levelScale());
    glBindVertexArray(frame.emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace glimmer
