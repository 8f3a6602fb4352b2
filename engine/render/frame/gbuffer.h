// The G-buffer (layout documented in shaders/frame/gbuffer.frag) and the HDR / display targets of a frame.
#pragma once
#include "gl/handles.h"

namespace glimmer {

class FrameTargets {
public:
    // Target 5 (KHR_materials_clearcoat) is read by the lighting pass at UNIT_GBUFFER_CLEARCOAT, not at
    // UNIT_GBUFFER_FIRST + 5 (the depth): see gbufferUnit().
    static constexpr int kGBufferColorCount = 6;

    // (Re)allocates when the size changes; `glintPost` also allocates the lighting pass's glint targets, and
    // `glintPart` the glint part target of TAA (below).
    void resize(int width, int height, bool glintPost = false, bool glintPart = false);
    int width() const { return width_; }
    int height() const { return height_; }
    // The image pipeline after TAA (exposure, bloom, tone mapping, the display image) runs at the post size: the
    // render size, or the output size when TAA upsamples (TAAU, docs/image.md). Call after resize().
    void resizePost(int width, int height);
    int postWidth() const { return postWidth_; }
    int postHeight() const { return postHeight_; }
    // The HDR radiance the post passes read: hdrTexture() itself at the render size, else a target of the post size
    // that the TAA pass resolves into.
    GLuint postHdrTexture() const { return postHdr_ ? postHdr_.id() : hdr_.id(); }

    GLuint gbufferFramebuffer() const { return gbufferFbo_.id(); }
    GLuint gbufferTexture(int i) const { return gbuffer_[i].id(); }
    GLuint depthTexture() const { return depth_.id(); }
    GLuint hdrFramebuffer() const { return hdrFbo_.id(); }
    // The lighting pass's shading class per pixel (render/frame/lighting_pass.h): DEPTH16 at the render size,
    // the depth attachment of the three lighting framebuffers; written through shadingClassFramebuffer().
    GLuint shadingClassFramebuffer() const { return shadingClassFbo_.id(); }
    GLuint shadingClassTexture() const { return shadingClass_.id(); }
    GLuint hdrTexture() const { return hdr_.id(); }
    GLuint displayFramebuffer() const { return displayFbo_.id(); }   // post size
    GLuint displayTexture() const { return display_.id(); }

    // Methods with a glint post pass (GlintMethod::glintPostPass). The lighting pass of such a method draws into
    // lightingGlintFramebuffer(): the HDR target plus glintEnvironmentTexture() (rgb: environment glints before
    // occlusion, a: visibility along the mirror direction) and glintLightsTexture() (rgb: light glints, a: 1 on
    // glinty pixels), which the method's passes read (their own intermediates are theirs).
    GLuint lightingGlintFramebuffer() const { return lightingGlintFbo_.id(); }
    GLuint glintEnvironmentTexture() const { return glintEnvironment_.id(); }
    GLuint glintLightsTexture() const { return glintLights_.id(); }

    // TAA (docs/image.md): the part of the lighting pass's radiance that is the lights' glints (location 3 of
    // lighting.frag), which the TAA pass keeps out of its neighbourhood clipping. When allocated it is attachment
    // 3 of lightingGlintPartFramebuffer() (the HDR target plus it) and of lightingGlintFramebuffer().
    GLuint lightingGlintPartFramebuffer() const { return lightingGlintPartFbo_.id(); }
    GLuint glintPartTexture() const { return glintPart_.id(); }

private:
    int width_ = 0, height_ = 0, postWidth_ = 0, postHeight_ = 0;
    gl::Texture postHdr_;   // empty when the post size is the render size
    gl::Texture gbuffer_[kGBufferColorCount];
    gl::Texture depth_, hdr_, display_, shadingClass_;
    gl::Framebuffer shadingClassFbo_;
    gl::Framebuffer gbufferFbo_, hdrFbo_, displayFbo_;
    void allocateGlintPost();
    gl::Texture glintEnvironment_, glintLights_;
    gl::Framebuffer lightingGlintFbo_;
    void allocateGlintPart();
    void attachGlintPart();   // to lightingGlintFbo_, when both exist
    gl::Texture glintPart_;
    gl::Framebuffer lightingGlintPartFbo_;
};

}  // namespace glimmer
