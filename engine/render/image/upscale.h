// Upscaling the renderer's display image (rendered at render_scale x the window) to the window's size with a
// Catmull-Rom cubic (shaders/image/upscale.frag), and the same filter on the CPU as the tests' reference.
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"

namespace glimmer {

class UpscalePass {
public:
    // Builds the program; throws gl::ShaderError with file:line.
    explicit UpscalePass(const std::filesystem::path& shaderRoot);
    // Draws `source` (sourceW x sourceH RGBA8) into the bound-by-id framebuffer over [0, targetW) x [0, targetH),
    // columns below `fromColumn` left as they are (the split view's right part). Copies exactly when the sizes match.
    void draw(GLuint sourceTexture, GLuint sourceFramebuffer, int sourceW, int sourceH, GLuint targetFramebuffer,
              int targetW, int targetH, int fromColumn = 0);
    const std::vector<std::filesystem::path>& dependencies() const { return program_.dependencies(); }

private:
    gl::Program program_;
    gl::VertexArray vao_;
};

// CPU reference: RGBA8 rows bottom-up (GL order) resampled like the shader (alpha set to 255). The shader
// computes in float and rounds on store; this one too, so results agree to one 8-bit step.
std::vector<uint8_t> catmullRomUpscale(const std::vector<uint8_t>& source, int sourceW, int sourceH, int targetW,
                                       int targetH);
// The same filter on RGBA32F radiance (all four channels), negative lobes' undershoot clamped to 0: what an
// offscreen render at render_scale < 1 without TAA upsampling returns as its HDR image (offscreen/offscreen.h).
std::vector<float> catmullRomUpscale(const std::vector<float>& source, int sourceW, int sourceH, int targetW,
                                     int targetH);

}  // namespace glimmer
