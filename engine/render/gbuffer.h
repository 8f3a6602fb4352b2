// The G-buffer (layout documented in shaders/gbuffer.frag) and the HDR / display targets of a frame.
#pragma once
#include "gl/handles.h"

namespace glimmer {

class FrameTargets {
public:
    static constexpr int kGBufferColorCount = 5;

    void resize(int width, int height);  // (re)allocates when the size changes
    int width() const { return width_; }
    int height() const { return height_; }

    GLuint gbufferFramebuffer() const { return gbufferFbo_.id(); }
    GLuint gbufferTexture(int i) const { return gbuffer_[i].id(); }
    GLuint depthTexture() const { return depth_.id(); }
    GLuint hdrFramebuffer() const { return hdrFbo_.id(); }
    GLuint hdrTexture() const { return hdr_.id(); }
    GLuint displayFramebuffer() const { return displayFbo_.id(); }
    GLuint displayTexture() const { return display_.id(); }

private:
    int width_ = 0, height_ = 0;
    gl::Texture gbuffer_[kGBufferColorCount];
    gl::Texture depth_, hdr_, display_;
    gl::Framebuffer gbufferFbo_, hdrFbo_, displayFbo_;
};

}  // namespace glimmer
