// An RGBA8 render target for UI tests: the UI renderer draws into it, the test reads its pixels back in UI
// coordinates (top-left origin).
#pragma once
#include <cstdint>
#include <vector>

#include "gl/handles.h"

namespace glimmer::test {

struct UiCanvas {
    int width, height;
    gl::Texture texture;
    gl::Framebuffer framebuffer;
    UiCanvas(int w, int h) : width(w), height(h) {
        texture = gl::createTexture2D(GL_RGBA8, w, h);
        GLuint fbo = 0;
        glCreateFramebuffers(1, &fbo);
        framebuffer = gl::Framebuffer(fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, texture.id(), 0);
        const float black[4] = {0, 0, 0, 1};
        glClearNamedFramebufferfv(fbo, GL_COLOR, 0, black);
    }
    std::vector<uint8_t> pixels() const {
        std::vector<uint8_t> p(size_t(width) * height * 4);
        glGetTextureImage(texture.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(p.size()), p.data());
        return p;
    }
    // RGBA of pixel (x, y) in UI coordinates within a readback of pixels().
    const uint8_t* at(const std::vector<uint8_t>& p, int x, int y) const {
        return &p[(size_t(height - 1 - y) * width + x) * 4];
    }
};

}  // namespace glimmer::test
