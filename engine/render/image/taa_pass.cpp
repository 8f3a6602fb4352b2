#include "render/image/taa_pass.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "gl/pipeline_state.h"
#include "gl/samplers.h"
#include "render/image/halton_jitter.h"
#include "common/bindings.glsl"

namespace glimmer {

namespace {
// A camera that moves more than this between frames is a cut (a preset, a teleport), not motion.
constexpr float kCutDistance = 2.0f;           // metres
constexpr float kCutCosine = 0.9f;             // ~26 degrees of rotation
}  // namespace

TaaPass::TaaPass(const std::filesystem::path& shaderRoot)
    : program_(shaderRoot, {"image/taa_resolve",
                            {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "image/taa_resolve.frag"}}}),
      upsample_(shaderRoot, {"image/taa_upsample",
                             {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "image/taa_upsample.frag"}}}) {
    linearClamp_ = gl::createLinearClampSampler();
}

bool TaaPass::wanted(const RenderSettings& settings) {
    return int(settings.value(param::aa)) == 1 && settings.debugView == 0 && !findIblMode(settings.ibl).accumulates;
}

void TaaPass::prepare(PrepareContext& context) {
    View& view = context.view;
    const RenderSettings& settings = context.settings;
    view.temporalAa = wanted(settings);
    // TAA upsampling: the history, the post passes and the display image at the output size. taa.upsample=0
    // resolves at the render size (the post passes then run on 1 / scale^2 fewer pixels) and leaves the upscale to
    // the caller.
    const bool upsample = view.temporalAa && settings.value(param::taa_upsample) > 0.5f &&
                          view.outputWidth >= view.width && view.outputHeight >= view.height &&
                          (view.outputWidth > view.width || view.outputHeight > view.height);
    view.postWidth = upsample ? view.outputWidth : view.width;
    view.postHeight = upsample ? view.outputHeight : view.height;
    view.jitter = glm::vec2(0.0f);
    if (view.temporalAa) {
        // TAA jitters the projection: a screen-space translation, so UV derivatives and glint footprints stay those
        // of the unjittered pixel (docs/image.md). AOVs and accumulating IBL modes stay unjittered.
        const Camera& camera = view.camera;
        view.jitter = beginFrame(camera.projection(view.aspect()) * camera.view(), camera.position, camera.forward(),
                                 view.width, view.height, view.postWidth, view.postHeight);
    } else {
        reset();
    }
    // The glint part at the render size while TAA runs (the lighting pass writes it).
    const FrameImage& hdr = context.resources.get(FrameResource::Hdr);
    if (view.temporalAa && (!glintPart_ || hdr.width != glintPartWidth_ || hdr.height != glintPartHeight_)) {
        // RGBA32F: glint radiance can exceed half-float range (one particle's radiance over a whole footprint).
        glintPart_ = gl::createTexture2D(GL_RGBA32F, hdr.width, hdr.height);
        glintPartWidth_ = hdr.width;
        glintPartHeight_ = hdr.height;
    }
    context.resources.publish(FrameResource::GlintPart,
                              glintPart_ ? FrameImage{.textures = {glintPart_.id()}, .width = glintPartWidth_,
                                                      .height = glintPartHeight_}
                                         : FrameImage{});
    // The HDR radiance the post passes read: Hdr itself at the render size, else a target of the post size.
    if (view.postWidth == hdr.width && view.postHeight == hdr.height) {
        postHdr_ = {};
        context.resources.publish(FrameResource::PostHdr, hdr);
    } else {
        if (!postHdr_ || postWidth_ != view.postWidth || postHeight_ != view.postHeight) {
            postHdr_ = gl::createTexture2D(GL_RGBA32F, view.postWidth, view.postHeight);
            postWidth_ = view.postWidth;
            postHeight_ = view.postHeight;
        }
        context.resources.publish(FrameResource::PostHdr,
                                  {.textures = {postHdr_.id()}, .width = postWidth_, .height = postHeight_});
    }
}

void TaaPass::resizeHistory(int width, int height) {
    if (width == width_ && height == height_) return;
    width_ = width;
    height_ = height;
    // RGBA32F throughout: glint radiance can exceed half-float range (one particle over a whole footprint).
    resolved_ = gl::createTexture2D(GL_RGBA32F, width, height);
    for (int i = 0; i < 2; ++i) {
        historyBase_[i] = gl::createTexture2D(GL_RGBA32F, width, height);
        historyGlint_[i] = gl::createTexture2D(GL_RGBA32F, width, height);
        GLuint fbo = 0;
        glCreateFramebuffers(1, &fbo);
        glObjectLabel(GL_FRAMEBUFFER, fbo, -1, "taa resolve");
        resolveFbo_[i] = gl::Framebuffer(fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, historyBase_[i].id(), 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, historyGlint_[i].id(), 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT2, resolved_.id(), 0);
        const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        glNamedFramebufferDrawBuffers(fbo, 3, buffers);
        if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error("framebuffer taa resolve incomplete");
    }
    reset();
}

glm::vec2 TaaPass::beginFrame(const glm::mat4& unjitteredViewProjection, glm::vec3 cameraPosition,
                              glm::vec3 forward, int width, int height, int outputWidth, int outputHeight) {
    resizeHistory(outputWidth, outputHeight);
    if (glm::distance(cameraPosition, previousPosition_) > kCutDistance ||
        glm::dot(glm::normalize(forward), previousForward_) < kCutCosine)
        reset();
    previousPosition_ = cameraPosition;
    previousForward_ = glm::normalize(forward);
    // Still: the same unjittered view as the last frame (the window's camera does not move without input).
    stillIndex_ = framesSinceReset_ > 0 && unjitteredViewProjection == viewProjection_ ? stillIndex_ + 1 : 0;
    previousViewProjection_ = framesSinceReset_ == 0 ? unjitteredViewProjection : viewProjection_;
    viewProjection_ = unjitteredViewProjection;
    const float ratio = std::max(float(outputWidth) / float(width), float(outputHeight) / float(height));
    phases_ = image::jitterPhases(ratio);
    jitter_ = image::haltonJitter(framesSinceReset_, phases_);
    return jitter_;
}

void TaaPass::execute(const FrameContext& frame) {
    const GLuint hdr = frame.resources.read(FrameResource::Hdr).texture();
    const GLuint glintPart = frame.resources.read(FrameResource::GlintPart).texture();
    const GLuint depth = frame.resources.read(FrameResource::Depth).texture();
    const GLuint postHdr = frame.resources.write(FrameResource::PostHdr).texture();
    resizeHistory(frame.postWidth, frame.postHeight);
    const bool upsampling = width_ != frame.width || height_ != frame.height;
    gl::Program& program = upsampling ? upsample_ : program_;
    const int previous = current_;
    current_ = 1 - current_;
    gl::fullscreenState(resolveFbo_[current_].id(), width_, height_).apply();
    program.use();
    glBindTextureUnit(UNIT_TAA_CURRENT, hdr);
    glBindTextureUnit(UNIT_TAA_GLINT_PART, glintPart);
    glBindTextureUnit(UNIT_TAA_DEPTH, depth);
    glBindTextureUnit(UNIT_TAA_HISTORY_BASE, historyBase_[previous].id());
    glBindTextureUnit(UNIT_TAA_HISTORY_GLINT, historyGlint_[previous].id());
    glBindSampler(UNIT_TAA_HISTORY_BASE, linearClamp_.id());
    glBindSampler(UNIT_TAA_HISTORY_GLINT, linearClamp_.id());
    const glm::mat4 reprojection = previousViewProjection_ * glm::inverse(viewProjection_);
    glProgramUniformMatrix4fv(program.id(), 0, 1, GL_FALSE, &reprojection[0][0]);
    glProgramUniform1i(program.id(), 1, framesSinceReset_ == 0 ? 1 : 0);
    glProgramUniform1f(program.id(), 2, frame.settings.value(param::taa_feedback));
    glProgramUniform1f(program.id(), 3, 1.25f);   // variance clip box half-size, standard deviations (Salvi 2016)
    glProgramUniform1i(program.id(), 4, frame.settings.value(param::taa_glint_history) > 0.5f ? 1 : 0);
    glProgramUniform1f(program.id(), 5, frame.settings.value(param::taa_glint_feedback));
    glProgramUniform1i(program.id(), 8, int(std::min(stillIndex_, 1u << 20)));
    glProgramUniform1i(program.id(), 9, phases_);
    if (upsampling) {
        glProgramUniform2f(program.id(), 6, jitter_.x, jitter_.y);
        glProgramUniform1f(program.id(), 7, kUpsampleKernelWidth);
    }
    glBindVertexArray(frame.emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindSampler(UNIT_TAA_HISTORY_BASE, 0);
    glBindSampler(UNIT_TAA_HISTORY_GLINT, 0);
    // The passes after this one read the post HDR target (the HDR target itself without upsampling).
    glCopyImageSubData(resolved_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, postHdr, GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
    ++framesSinceReset_;
}

}  // namespace glimmer
