#include "render/shadows/shadow_mask_pass.h"

#include "common/bindings.glsl"
#include "gl/pipeline_state.h"
#include "render/shadows/shadow_maps.h"

namespace glimmer {

ShadowMaskPass::ShadowMaskPass(const std::filesystem::path& shaderRoot, std::shared_ptr<ShadowMaps> shadows)
    : shaderRoot_(shaderRoot), shadows_(std::move(shadows)) {
    // The sun alone, the most common case, built now so that a broken shader fails at construction.
    programFor(glm::ivec4(int(ShadowFilter::Cascades), 0, 0, 0));
}

gl::Program& ShadowMaskPass::programFor(const glm::ivec4& filters) {
    const std::string value = "ivec4(" + std::to_string(filters.x) + ", " + std::to_string(filters.y) + ", " +
                              std::to_string(filters.z) + ", " + std::to_string(filters.w) + ")";
    std::unique_ptr<gl::Program>& program = programs_[value];
    if (!program)
        program = std::make_unique<gl::Program>(
            shaderRoot_, gl::ProgramDesc{"shadow_mask",
                                         {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                          {GL_FRAGMENT_SHADER, "shadows/shadow_mask.frag"}},
                                         {"SHADOW_MASK_FILTERS " + value}});
    return *program;
}

std::vector<gl::Program*> ShadowMaskPass::programs() {
    std::vector<gl::Program*> all;
    for (auto& [filters, program] : programs_) all.push_back(program.get());
    return all;
}

void ShadowMaskPass::prepare(PrepareContext& context) {
    if (shadows_->settings().enabled && !context.blendSample) {
        shadows_->ensureMask(context.view.width, context.view.height);
        for (int layer = 0; layer < shadows_->maskLayers(); ++layer) programFor(shadows_->maskLayerFilters(layer));
    }
    context.resources.publish(FrameResource::ShadowMask, shadows_->maskImage());
}

bool ShadowMaskPass::runs(const FrameContext& frame) const {
    return shadows_->settings().enabled && !frame.blendSample;
}

void ShadowMaskPass::execute(const FrameContext& frame) {
    const FrameImage& maps = frame.resources.read(FrameResource::ShadowMaps);
    const FrameImage& gbuffer = frame.resources.read(FrameResource::GBuffer);
    const GLuint depth = frame.resources.read(FrameResource::Depth).texture();
    frame.resources.write(FrameResource::ShadowMask);
    // One draw per layer of four shadowed lights (the mask's texture is unbound while it is the target).
    for (int layer = 0; layer < shadows_->maskLayers(); ++layer) {
        const GLuint framebuffer = shadows_->maskFramebuffer(layer);
        const glm::ivec2 size = shadows_->maskSize();
        gl::fullscreenState(framebuffer, size.x, size.y).apply();
        const gl::Program& program = programFor(shadows_->maskLayerFilters(layer));
        program.use();
        bindShadowInputs(maps, {});
        glProgramUniform1i(program.id(), 0, layer);
        glBindTextureUnit(UNIT_GBUFFER_NORMAL_ALPHA, gbuffer.texture(UNIT_GBUFFER_NORMAL_ALPHA - UNIT_GBUFFER_FIRST));
        glBindTextureUnit(UNIT_GBUFFER_DEPTH, depth);
        glBindVertexArray(frame.emptyVao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
}

}  // namespace glimmer
