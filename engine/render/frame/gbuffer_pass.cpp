#include "render/frame/gbuffer_pass.h"

#include "gl/pipeline_state.h"
#include "glints/methods.h"

namespace glimmer {
namespace {

gl::ProgramDesc gbufferProgramDesc(bool slopeCovariance, bool extraTextures) {
    gl::ProgramDesc desc{slopeCovariance ? "gbuffer/slope covariance" : "gbuffer",
                         {{GL_VERTEX_SHADER, "frame/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "frame/gbuffer.frag"}}};
    if (slopeCovariance) desc.defines.push_back("GBUFFER_SLOPE_COVARIANCE");
    if (extraTextures) desc.defines.push_back("GBUFFER_EXTRA_TEXTURES");
    return desc;
}

// Whether a material of the scene has an occlusion, glint-mask or clear-coat texture.
bool sceneUsesExtraTextures(const Scene& scene) {
    for (const Material& m : scene.materials)
        if (m.occlusionTexture >= 0 || m.glintMaskTexture >= 0 || m.clearcoatTexture >= 0 ||
            m.clearcoatRoughnessTexture >= 0 || m.clearcoatNormalTexture >= 0)
            return true;
    return false;
}

}  // namespace

GBufferPass::GBufferPass(const std::filesystem::path& shaderRoot)
    : shaderRoot_(shaderRoot), program_(shaderRoot, gbufferProgramDesc(false, extraTextures_)) {}

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
    // A material with one of the extra textures appeared or went (a scene): the programs with or without them.
    if (const bool extra = sceneUsesExtraTextures(context.scene); extra != extraTextures_) {
        gl::Program fresh(shaderRoot_, gbufferProgramDesc(false, extra));
        program_ = std::move(fresh);
        slopeProgram_.reset();
        extraTextures_ = extra;
    }
    const bool wanted = findGlintMethod(context.settings.method).slopeCovariance;
    if (wanted) {
        context.gpuScene.ensureLeanMaps(context.scene);
        if (!slopeProgram_)
            slopeProgram_ = std::make_unique<gl::Program>(shaderRoot_, gbufferProgramDesc(true, extraTextures_));
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
