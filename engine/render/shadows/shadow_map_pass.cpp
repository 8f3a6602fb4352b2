#include "render/shadows/shadow_map_pass.h"

#include <glm/gtc/type_ptr.hpp>

#include "gl/pipeline_state.h"

namespace glimmer {

ShadowMapPass::ShadowMapPass(const std::filesystem::path& shaderRoot, ShadowArray array,
                             std::shared_ptr<ShadowMaps> shadows)
    : unmasked_(shaderRoot, {"shadow_depth", {{GL_VERTEX_SHADER, "shadows/shadow_depth.vert"},
                                              {GL_FRAGMENT_SHADER, "shadows/shadow_depth.frag"}}}),
      masked_(shaderRoot, {"shadow_depth_masked", {{GL_VERTEX_SHADER, "shadows/shadow_depth.vert"},
                                                   {GL_FRAGMENT_SHADER, "shadows/shadow_depth.frag"}}, {"ALPHA_MASK"}}),
      array_(array),
      shadows_(std::move(shadows)) {}

void ShadowMapPass::prepare(PrepareContext& context) {
    if (array_ != ShadowArray::Sun) return;   // the sun pass fits every light's views, once per frame
    // Shadow views fitted to this camera (only the invalidated ones are rendered); a later sample of an accumulated
    // view keeps sample 0's.
    if (!context.blendSample)
        shadows_->prepare(context.scene, context.gpuScene, context.view.camera, context.view.aspect(), context.settings);
    context.resources.publish(FrameResource::ShadowMaps, shadows_->mapsImage());
}

bool ShadowMapPass::runs(const FrameContext& frame) const {
    if (frame.blendSample) return false;
    for (const ShadowView& view : shadows_->views())
        if (view.array == array_) return true;
    return false;
}

void ShadowMapPass::execute(const FrameContext& frame) {
    ShadowMaps& shadows = *shadows_;
    for (ShadowView& view : shadows.views()) {
        if (view.array != array_ || !view.dirty) continue;
        const int size = shadows.mapSizeOf(view);
        gl::PipelineState state = gl::fullscreenState(shadows.framebufferFor(view), size, size);
        state.depthTest = true;
        state.depthFunc = GL_GREATER;
        state.depthWrite = true;
        // Reversed Z: away from the light is towards 0, so both terms are negative.
        state.polygonOffset = {-shadows.settings().slopeBias, -1.0f};
        state.apply();
        const float clearDepth = 0.0f;
        glClearNamedFramebufferfv(state.framebuffer, GL_DEPTH, 0, &clearDepth);
        for (gl::Program* program : {&unmasked_, &masked_}) {
            program->use();
            glUniformMatrix4fv(5, 1, GL_FALSE, glm::value_ptr(view.viewProjection));
            frame.gpuScene.drawInstances(frame.scene, view.viewProjection,
                                         program == &unmasked_ ? DrawSelection::DepthOnlyUnmasked
                                                               : DrawSelection::DepthOnlyMasked);
        }
        view.dirty = false;
        (array_ == ShadowArray::Sun ? shadows.stats().sunViewsRendered : shadows.stats().localViewsRendered) += 1;
        shadows.stats().trianglesDrawn += frame.gpuScene.lastDrawStats().trianglesDrawn;
    }
}

}  // namespace glimmer
