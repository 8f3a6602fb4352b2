#include "render/shadows/shadow_mask_pass.h"

#include "common/bindings.glsl"
#include "gl/pipeline_state.h"
#include "render/shadows/shadow_maps.h"

namespace glimmer {

ShadowMaskPass::ShadowMaskPass(const std::filesystem::path& shaderRoot)
    : program_(shaderRoot,
               {"shadow_mask", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "shadows/shadow_mask.frag"}}}) {}

bool ShadowMaskPass::runs(const FrameContext& frame) const {
    return frame.shadows && frame.shadows->settings().enabled && !frame.blendSample;
}

void ShadowMaskPass::execute(const FrameContext& frame) {
    // One draw per layer of four shadowed lights (the mask's texture is unbound while it is the target).
    for (int layer = 0; layer < frame.shadows->maskLayers(); ++layer) {
        const GLuint framebuffer = frame.shadows->maskFramebuffer(frame.width, frame.height, layer);
        const glm::ivec2 size = frame.shadows->maskSize();
        gl::fullscreenState(framebuffer, size.x, size.y).apply();
        program_.use();
        frame.shadows->bind();
        glBindTextureUnit(UNIT_SHADOW_MASK, 0);
        glProgramUniform1i(program_.id(), 0, layer);
        glBindTextureUnit(UNIT_GBUFFER_NORMAL_ALPHA,
                          frame.targets.gbufferTexture(UNIT_GBUFFER_NORMAL_ALPHA - UNIT_GBUFFER_FIRST));
        glBindTextureUnit(UNIT_GBUFFER_DEPTH, frame.targets.depthTexture());
        glBindVertexArray(frame.emptyVao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
}

}  // namespace glimmer
