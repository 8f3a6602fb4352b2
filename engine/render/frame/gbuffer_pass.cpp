#include "render/frame/gbuffer_pass.h"

#include "gl/pipeline_state.h"
#include "glints/methods.h"

namespace glimmer {

GBufferPass::GBufferPass(const std::filesystem::path& shaderRoot)
    : shaderRoot_(shaderRoot),
      program_(shaderRoot, {"gbuffer", {{GL_VERTEX_SHADER, "frame/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "frame/gbuffer.frag"}}}) {}

std::vector<gl::Program*> GBufferPass::programs() {
    std::vector<gl::Program*> all{&program_};
    if (slopeProgram_) all.push_back(slopeProgram_.get());
    return all;
}

void GBufferPass::publish(FrameResources& resources) const {
    FrameImage gbuffer{.width = width_, .height = height_};
    for (int i = 0; i < kColorCount; ++i) gbuffer.textures.push_back(colors_[i].id());
    if (slopeCovariance_) gbuffer.textures.push_back(slopeTarget_.id());
    resources.publish(FrameResource::GBuffer, std::move(gbuffer));
}

void GBufferPass::resize(const View& view, FrameResources& resources) {
    // Target 5, the clear coat: half floats keep the coat normal's octahedral code fine enough for a mirror-like
    // coat (8 bits would band its highlight); 8 bytes a pixel.
    static const GLenum formats[kColorCount] = {GL_RGBA32F, GL_RGBA32F, GL_RGBA16F, GL_RGBA16F, GL_RGBA8, GL_RGBA16F};
    width_ = view.width;
    height_ = view.height;
    for (int i = 0; i < kColorCount; ++i) colors_[i] = gl::createTexture2D(formats[i], view.width, view.height);
    depth_ = gl::createTexture2D(GL_DEPTH_COMPONENT32F, view.width, view.height);
    static_assert(kColorCount == 6, "attachments below");
    framebuffer_ = gl::createFramebuffer("gbuffer",
                                         {colors_[0].id(), colors_[1].id(), colors_[2].id(), colors_[3].id(),
                                          colors_[4].id(), colors_[5].id()},
                                         depth_.id());
    slopeTarget_ = {};   // reallocated at the new size by prepare() when a method reads it
    slopeFramebuffer_ = {};
    slopeCovariance_ = false;
    publish(resources);
    resources.publish(FrameResource::Depth, {.textures = {depth_.id()}, .width = view.width, .height = view.height});
}

void GBufferPass::prepare(PrepareContext& context) {
    context.gpuScene.setTextureAnisotropy(context.settings.value(param::texture_anisotropy));
    const bool wanted = findGlintMethod(context.settings.method).slopeCovariance;
    if (wanted) {
        context.gpuScene.ensureLeanMaps(context.scene);
        if (!slopeProgram_) {
            gl::ProgramDesc desc{"gbuffer/slope covariance",
                                 {{GL_VERTEX_SHADER, "frame/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "frame/gbuffer.frag"}}};
            desc.defines = {"GBUFFER_SLOPE_COVARIANCE"};
            slopeProgram_ = std::make_unique<gl::Program>(shaderRoot_, desc);
        }
        if (!slopeTarget_) {
            // Half floats: the covariance of slopes (0 .. ~1 for real normal maps) needs no more; 8 bytes a pixel.
            slopeTarget_ = gl::createTexture2D(GL_RGBA16F, width_, height_);
            slopeFramebuffer_ = gl::createFramebuffer(
                "gbuffer+slope covariance",
                {colors_[0].id(), colors_[1].id(), colors_[2].id(), colors_[3].id(), colors_[4].id(), colors_[5].id(),
                 slopeTarget_.id()},
                depth_.id());
        }
    }
    if (wanted != slopeCovariance_) {
        slopeCovariance_ = wanted;
        publish(context.resources);
    }
}

void GBufferPass::execute(const FrameContext& frame) {
    const GLuint framebuffer = slopeCovariance_ ? slopeFramebuffer_.id() : framebuffer_.id();
    gl::PipelineState state = gl::fullscreenState(framebuffer, frame.width, frame.height);
    state.depthTest = true;
    state.depthFunc = GL_GREATER;
    state.depthWrite = true;
    state.apply();
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < kColorCount + (slopeCovariance_ ? 1 : 0); ++i)
        glClearNamedFramebufferfv(framebuffer, GL_COLOR, i, zero);
    const float clearDepth = 0.0f;
    glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &clearDepth);
    (slopeCovariance_ ? *slopeProgram_ : program_).use();
    // GpuScene culls frustum chunks and, on single-sided materials, back faces (it sets and resets the cull state),
    // and draws each chunk at the level of detail lod.pixel_error allows at this frame's (render) size.
    frame.gpuScene.drawInstances(frame.scene, frame.viewProjection, DrawSelection::Opaque, geometryLod(frame));
}

}  // namespace glimmer
