// The window image, and screenshots of it.
#pragma once
#include <glad/gl.h>

#include <cstdint>
#include <string>
#include <vector>

#include "gl/handles.h"
#include "render/renderer.h"

namespace glimmer {

// The window image: the renderer's display image with the UI drawn over it. Rendering the overlay into our own
// texture (not the window) keeps screenshots independent of the window system.
class PresentTarget {
public:
    void resize(int width, int height);
    GLuint framebuffer() const { return framebuffer_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }
    std::vector<uint8_t> read() const;   // RGBA8, opaque

private:
    int width_ = 0, height_ = 0;
    gl::Texture texture_;
    gl::Framebuffer framebuffer_;
};

// PNG: the window image (with the UI when shown). EXR: the renderer's HDR radiance (or debug view), linear.
void writeWindowScreenshot(const std::string& path, const Renderer& renderer, const PresentTarget& window);

// glimmer-<scene>-001<extension>, the first such name not yet taken in the current folder.
std::string nextScreenshotName(const std::string& sceneName, const char* extension);

}  // namespace glimmer
