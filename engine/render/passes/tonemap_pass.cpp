#include "render/passes/tonemap_pass.h"

#include "gl/pipeline_state.h"
#include "common/bindings.glsl"

namespace glimmer {

TonemapPass::TonemapPass(const std::filesystem::path& shaderRoot)
    : program_(shaderRoot, {"tonemap", {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "tonemap.frag"}}}) {}

void TonemapPass::execute(const FrameContext& frame) {
    gl::fullscreenState(frame.targets.displayFramebuffer(), frame.width, frame.height).apply();
    program_.use();
    glBindTextureUnit(UNIT_TONEMAP_HDR, frame.targets.hdrTexture());
    glBindVertexArray(frame.emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace glimmer
