#include "render/frame/gbuffer.h"

#include "core/error.h"

namespace glimmer {

static void checkComplete(GLuint fbo, const char* name) {
    GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(std::string("framebuffer ") + name + " incomplete (status 0x" + std::to_string(status) + ")");
}

// The glint part sits on attachment 3 with gaps before it (and joins the glint framebuffer later), so these
// two are built attachment by attachment rather than by gl::createFramebuffer.
static gl::Framebuffer labelledFramebuffer(const char* label) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    glObjectLabel(GL_FRAMEBUFFER, id, -1, label);
    return gl::Framebuffer(id);
}

void FrameTargets::resize(int width, int height, bool glintPost, bool glintPart) {
    if (width == width_ && height == height_) {
        if (glintPost && !glintEnvironment_) allocateGlintPost();
        if (glintPart && !glintPart_) allocateGlintPart();
        return;
    }
    // Post targets of another size than the render size (TAA upsampling) survive a render-size change: dynamic
    // resolution changes it every few frames while the output size stays.
    const bool postWasRenderSize = postWidth_ == width_ && postHeight_ == height_;
    width_ = width;
    height_ = height;
    glintEnvironment_ = {};  // reallocated below at the new size when needed
    glintPart_ = {};
    // Target 5, the clear coat: half floats keep the coat normal's octahedral code fine enough for a mirror-like
    // coat (8 bits would band its highlight); 8 bytes a pixel.
    static const GLenum formats[kGBufferColorCount] = {GL_RGBA32F, GL_RGBA32F, GL_RGBA16F, GL_RGBA16F, GL_RGBA8,
                                                       GL_RGBA16F};
    for (int i = 0; i < kGBufferColorCount; ++i) gbuffer_[i] = gl::createTexture2D(formats[i], width, height);
    static_assert(kGBufferColorCount == 6, "attachments below");
    depth_ = gl::createTexture2D(GL_DEPTH_COMPONENT32F, width, height);
    gbufferFbo_ = gl::createFramebuffer(
        "gbuffer", {gbuffer_[0].id(), gbuffer_[1].id(), gbuffer_[2].id(), gbuffer_[3].id(), gbuffer_[4].id(),
                     gbuffer_[5].id()},
        depth_.id());
    hdr_ = gl::createTexture2D(GL_RGBA32F, width, height);
    shadingClass_ = gl::createTexture2D(GL_DEPTH_COMPONENT16, width, height);
    shadingClassFbo_ = labelledFramebuffer("shading class");
    glNamedFramebufferTexture(shadingClassFbo_.id(), GL_DEPTH_ATTACHMENT, shadingClass_.id(), 0);
    glNamedFramebufferDrawBuffer(shadingClassFbo_.id(), GL_NONE);
    checkComplete(shadingClassFbo_.id(), "shading class");
    hdrFbo_ = gl::createFramebuffer("hdr", {hdr_.id()}, shadingClass_.id());
    if (postWasRenderSize || !display_) {
        postWidth_ = postHeight_ = 0;
        resizePost(width, height);   // the renderer asks for another post size when TAA upsamples
    } else if (postWidth_ == width && postHeight_ == height) {
        postHdr_ = {};               // the post size is the render size now: the HDR target itself
    }
    if (glintPost) allocateGlintPost();
    if (glintPart) allocateGlintPart();
}

void FrameTargets::resizePost(int width, int height) {
    if (width == postWidth_ && height == postHeight_) return;
    postWidth_ = width;
    postHeight_ = height;
    postHdr_ = width == width_ && height == height_ ? gl::Texture{} : gl::createTexture2D(GL_RGBA32F, width, height);
    display_ = gl::createTexture2D(GL_RGBA8, width, height);
    displayFbo_ = gl::createFramebuffer("display", {display_.id()});
}

void FrameTargets::allocateGlintPost() {
    // RGBA32F: a micro-scale glint can exceed half-float range (one particle's radiance over a whole footprint).
    glintEnvironment_ = gl::createTexture2D(GL_RGBA32F, width_, height_);
    glintLights_ = gl::createTexture2D(GL_RGBA32F, width_, height_);
    lightingGlintFbo_ = gl::createFramebuffer("lighting+glints", {hdr_.id(), glintEnvironment_.id(), glintLights_.id()},
                                              shadingClass_.id());
    attachGlintPart();
}

void FrameTargets::allocateGlintPart() {
    // RGBA32F for the same reason as the glint targets above.
    glintPart_ = gl::createTexture2D(GL_RGBA32F, width_, height_);
    lightingGlintPartFbo_ = labelledFramebuffer("lighting+glint part");
    glNamedFramebufferTexture(lightingGlintPartFbo_.id(), GL_COLOR_ATTACHMENT0, hdr_.id(), 0);
    glNamedFramebufferTexture(lightingGlintPartFbo_.id(), GL_COLOR_ATTACHMENT3, glintPart_.id(), 0);
    glNamedFramebufferTexture(lightingGlintPartFbo_.id(), GL_DEPTH_ATTACHMENT, shadingClass_.id(), 0);
    const GLenum drawBuffers[4] = {GL_COLOR_ATTACHMENT0, GL_NONE, GL_NONE, GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(lightingGlintPartFbo_.id(), 4, drawBuffers);
    checkComplete(lightingGlintPartFbo_.id(), "lighting+glint part");
    attachGlintPart();
}

void FrameTargets::attachGlintPart() {
    if (!glintPart_ || !lightingGlintFbo_) return;
    // Methods with a glint post pass add their glints after the lighting pass: their glint part is zero.
    glNamedFramebufferTexture(lightingGlintFbo_.id(), GL_COLOR_ATTACHMENT3, glintPart_.id(), 0);
    const GLenum drawBuffers[4] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                   GL_COLOR_ATTACHMENT3};
    glNamedFramebufferDrawBuffers(lightingGlintFbo_.id(), 4, drawBuffers);
    checkComplete(lightingGlintFbo_.id(), "lighting+glints+glint part");
}

}  // namespace glimmer
