// The largest frame a render may ask for (--size, and the supersampled size of aa=ssaa), checked before any
// frame target is allocated: a 16384 x 16384 request allocated over 6 GB and then failed with "framebuffer gbuffer
// incomplete". Each side must be within the context's limits (GL_MAX_TEXTURE_SIZE, GL_MAX_FRAMEBUFFER_WIDTH /
// HEIGHT, GL_MAX_VIEWPORT_DIMS), and the frame's targets and readbacks, kFrameBytesPerPixel each pixel, must fit
// in the memory available (MemAvailable of /proc/meminfo: llvmpipe's targets live in system memory; a GPU's
// own memory is not known portably, so the same bound applies there to the readbacks).
#pragma once
#include <cstdint>
#include <string>

namespace glimmer {

// Frame targets (G-buffer 60 bytes, depth, HDR, display, glint targets, TAA history, bloom and AO levels) and the
// CPU readbacks of a render, per output pixel: twice the most measured on llvmpipe (peak resident memory between
// 256^2 and 2048^2 renders grew 120 bytes a pixel on plane90 without environment, 204 on the atrium with TAA and
// the environment; docs/hostile_input.md).
constexpr uint64_t kFrameBytesPerPixel = 400;

struct FrameSizeLimit {
    int maxSide = 0;                 // pixels, the smallest of the GL limits
    uint64_t availableBytes = 0;     // 0 when unknown (then only the side limit applies)
};

// Needs a current GL context.
FrameSizeLimit frameSizeLimit();

// Throws UsageError naming `flag` when width x height exceeds `limit`.
void checkFrameSize(int width, int height, const FrameSizeLimit& limit, const std::string& flag);

}  // namespace glimmer
