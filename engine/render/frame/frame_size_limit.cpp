#include "render/frame/frame_size_limit.h"

#include <glad/gl.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "core/error.h"

namespace glimmer {
namespace {

// MemAvailable in bytes, 0 when /proc/meminfo has none.
uint64_t memoryAvailable() {
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    uint64_t kib = 0;
    std::string unit;
    while (meminfo >> key >> kib >> unit)
        if (key == "MemAvailable:") return kib * 1024;
    return 0;
}

}  // namespace

FrameSizeLimit frameSizeLimit() {
    GLint texture = 0, width = 0, height = 0, viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_WIDTH, &width);
    glGetIntegerv(GL_MAX_FRAMEBUFFER_HEIGHT, &height);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    FrameSizeLimit limit;
    limit.maxSide = std::min({texture, width, height, viewport[0], viewport[1]});
    limit.availableBytes = memoryAvailable();
    return limit;
}

void checkFrameSize(int width, int height, const FrameSizeLimit& limit, const std::string& flag) {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (limit.maxSide > 0 && (width > limit.maxSide || height > limit.maxSide))
        throw UsageError(flag + ": " + size + " exceeds this GL context's largest frame side of " +
                         std::to_string(limit.maxSide) + " pixels");
    const uint64_t needed = uint64_t(width) * uint64_t(height) * kFrameBytesPerPixel;
    if (limit.availableBytes > 0 && needed > limit.availableBytes) {
        char text[256];
        std::snprintf(text, sizeof text, ": %s needs about %.1f GiB of frame targets and readbacks (%llu bytes a pixel), "
                      "over the %.1f GiB of memory available", size.c_str(), double(needed) / double(1ull << 30),
                      (unsigned long long)kFrameBytesPerPixel, double(limit.availableBytes) / double(1ull << 30));
        throw UsageError(flag + text);
    }
}

}  // namespace glimmer
