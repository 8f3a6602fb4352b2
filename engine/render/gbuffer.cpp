#include "render/gbuffer.h"

#include "core/error.h"

namespace glimmer {

static void checkComplete(GLuint fbo, const char* name) {
    GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(std::string("framebuffer ") + name + " incomplete (status 0x" + std::to_string(status) + ")");
}

static gl::Framebuffer createFramebuffer(const char* label) {
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
    width_ = width;
    height_ = height;
    glintEnvironment_ = {};  // reallocated below at the new size when needed
    glintPart_ = {};
    static const GLenum formats[kGBufferColorCount] = {GL_RGBA32F, GL_RGBA32F, GL_RGBA16F, GL_RGBA16F, GL_RGBA8};
    gbufferFbo_ = createFramebuffer("gbuffer");
    GLenum drawBuffers[kGBufferColorCount];
    for (int i = 0; i < kGBufferColorCount; ++i) {
        gbuffer_[i] = gl::createTexture2D(formats[i], width, height);
        glNamedFramebufferTexture(gbufferFbo_.id(), GL_COLOR_ATTACHMENT0 + i, gbuffer_[i].id(), 0);
        drawBuffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    glNamedFramebufferDrawBuffers(gbufferFbo_.id(), kGBufferColorCount, drawBuffers);
    depth_ = gl::createTexture2D(GL_DEPTH_COMPONENT32F, width, height);
    glNamedFramebufferTexture(gbufferFbo_.id(), GL_DEPTH_ATTACHMENT, depth_.id(), 0);
    checkComplete(gbufferFbo_.id(), "gbuffer");

    hdrFbo_ = createFramebuffer("hdr");
    hdr_ = gl::createTexture2D(GL_RGBA32F, width, height);
    glNamedFramebufferTexture(hdrFbo_.id(), GL_COLOR_ATTACHMENT0, hdr_.id(), 0);
    checkComplete(hdrFbo_.id(), "hdr");

    displayFbo_ = createFramebuffer("display");
    display_ = gl::createTexture2D(GL_RGBA8, width, height);
    glNamedFramebufferTexture(displayFbo_.id(), GL_COLOR_ATTACHMENT0, display_.id(), 0);
    checkComplete(displayFbo_.id(), "display");
    if (glintPost) allocateGlintPost();
    if (glintPart) allocateGlintPart();
}

void FrameTargets::allocateGlintPost() {
    // RGBA32F: a micro-scale glint can exceed half-float range (one particle's radiance over a whole footprint).
    glintEnvironment_ = gl::createTexture2D(GL_RGBA32F, width_, height_);
    glintLights_ = gl::createTexture2D(GL_RGBA32F, width_, height_);
    lightingGlintFbo_ = createFramebuffer("lighting+glints");
    glNamedFramebufferTexture(lightingGlintFbo_.id(), GL_COLOR_ATTACHMENT0, hdr_.id(), 0);
    glNamedFramebufferTexture(lightingGlintFbo_.id(), GL_COLOR_ATTACHMENT1, glintEnvironment_.id(), 0);
    glNamedFramebufferTexture(lightingGlintFbo_.id(), GL_COLOR_ATTACHMENT2, glintLights_.id(), 0);
    const GLenum drawBuffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(lightingGlintFbo_.id(), 3, drawBuffers);
    checkComplete(lightingGlintFbo_.id(), "lighting+glints");
    attachGlintPart();
}

void FrameTargets::allocateGlintPart() {
    // RGBA32F for the same reason as the glint targets above.
    glintPart_ = gl::createTexture2D(GL_RGBA32F, width_, height_);
    lightingGlintPartFbo_ = createFramebuffer("lighting+glint part");
    glNamedFramebufferTexture(lightingGlintPartFbo_.id(), GL_COLOR_ATTACHMENT0, hdr_.id(), 0);
    glNamedFramebufferTexture(lightingGlintPartFbo_.id(), GL_COLOR_ATTACHMENT3, glintPart_.id(), 0);
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
