#include "render/frame/gbuffer_pass.h"

#include "gl/pipeline_state.h"

namespace glimmer {

GBufferPass::GBufferPass(const std::filesystem::path& shaderRoot)
    : program_(shaderRoot, {"gbuffer", {{GL_VERTEX_SHADER, "frame/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "frame/gbuffer.frag"}}}) {}

void GBufferPass::resize(const View& view, FrameResources& resources) {
    // Target 5, the clear coat: half floats keep the coat normal's octahedral code fine enough for a mirror-like
    // coat (8 bits would band its highlight); 8 bytes a pixel.
    static const GLenum formats[kColorCount] = {GL_RGBA32F, GL_RGBA32F, GL_RGBA16F, GL_RGBA16F, GL_RGBA8, GL_RGBA16F};
    FrameImage gbuffer{.width = view.width, .height = view.height};
    for (int i = 0; i < kColorCount; ++i) {
        colors_[i] = gl::createTexture2D(formats[i], view.width, view.height);
        gbuffer.textures.push_back(colors_[i].id());
    }
    depth_ = gl::createTexture2D(GL_DEPTH_COMPONENT32F, view.width, view.height);
    static_assert(kColorCount == 6, "attachments below");
    framebuffer_ = gl::createFramebuffer("gbuffer",
                                         {colors_[0].id(), colors_[1].id(), colors_[2].id(), colors_[3].id(),
                                          colors_[4].id(), colors_[5].id()},
                                         depth_.id());
    resources.publish(FrameResource::GBuffer, std::move(gbuffer));
    resources.publish(FrameResource::Depth, {.textures = {depth_.id()}, .width = view.width, .height = view.height});
}

void GBufferPass::prepare(PrepareContext& context) {
    context.gpuScene.setTextureAnisotropy(context.settings.value(param::texture_anisotropy));
}

void GBufferPass::execute(const FrameContext& frame) {
    gl::PipelineState state = gl::fullscreenState(framebuffer_.id(), frame.width, frame.height);
    state.depthTest = true;
    state.depthFunc = GL_GREATER;
    state.depthWrite = true;
    state.apply();
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < kColorCount; ++i) glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, i, zero);
    const float clearDepth = 0.0f;
    glClearNamedFramebufferfv(framebuffer_.id(), GL_DEPTH, 0, &clearDepth);
    program_.use();
    // GpuScene culls frustum chunks and, on single-sided materials, back faces (it sets and resets the cull state),
    // and draws each chunk at the level of detail lod.pixel_error allows at this frame's (render) size.
    frame.gpuScene.drawInstances(frame.scene, frame.viewProjection, DrawSelection::Opaque, geometryLod(frame));
}

}  // namespace glimmer
