// Image files through OpenImageIO: PNG (8-bit sRGB) and EXR (32-bit float linear). Pixel rows passed in are
// bottom-up (GL order) and written top-down. Errors name the file.
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

namespace glimmer {

struct ImageF {
    int width = 0, height = 0, channels = 0;
    std::vector<float> pixels;  // top-down rows, interleaved channels
    float at(int x, int y, int c) const { return pixels[(size_t(y) * width + x) * channels + c]; }
};

void writePng(const std::filesystem::path& path, const uint8_t* rgbaBottomUp, int width, int height);
void writeExr(const std::filesystem::path& path, const float* rgbaBottomUp, int width, int height, int channels = 4);
// Writes top-down float pixels as PNG (values clamped to [0,1], no tone mapping) or EXR by extension.
void writeImage(const std::filesystem::path& path, const ImageF& image);
// Reads any format OpenImageIO knows into floats (PNG values in [0,1], sRGB-encoded as stored).
ImageF readImage(const std::filesystem::path& path);

// Throws UsageError naming --out when the path has no supported extension (.png or .exr).
enum class ImageFormat { Png, Exr };
ImageFormat imageFormatForPath(const std::filesystem::path& path, const char* flag);

}  // namespace glimmer
