#include "app/walkthrough/present.h"

#include <cstdio>
#include <filesystem>

#include "core/image_io.h"

namespace glimmer {

void PresentTarget::resize(int width, int height) {
    if (width == width_ && height == height_) return;
    width_ = width;
    height_ = height;
    texture_ = gl::createTexture2D(GL_RGBA8, width, height);
    framebuffer_ = gl::createFramebuffer("walkthrough present", {texture_.id()});
}

std::vector<uint8_t> PresentTarget::read() const {
    std::vector<uint8_t> pixels(size_t(width_) * height_ * 4);
    glGetTextureImage(texture_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    for (size_t i = 3; i < pixels.size(); i += 4) pixels[i] = 255;
    return pixels;
}

void writeWindowScreenshot(const std::string& path, const Renderer& renderer, const PresentTarget& window) {
    int width = renderer.lastView().postWidth, height = renderer.lastView().postHeight;
    if (imageFormatForPath(path, "--screenshot") == ImageFormat::Exr) {
        std::vector<float> hdr = renderer.readHdr();
        writeExr(path, hdr.data(), width, height);
    } else {
        std::vector<uint8_t> pixels = window.read();   // the window image, window size (render scale < 1)
        writePng(path, pixels.data(), window.width(), window.height());
    }
}

std::string nextScreenshotName(const std::string& sceneName, const char* extension) {
    for (int i = 1;; ++i) {
        char name[256];
        std::snprintf(name, sizeof name, "glimmer-%s-%03d%s", sceneName.c_str(), i, extension);
        if (!std::filesystem::exists(name)) return name;
    }
}

}  // namespace glimmer
