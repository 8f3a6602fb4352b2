// Image files through OpenImageIO: PNG (8-bit sRGB) and EXR (32-bit float linear) out; PNG, JPEG, Radiance HDR
// and OpenEXR in. Pixel rows passed in are bottom-up (GL order) and written top-down. Errors name the file.
// Writes are atomic (core/atomic_file.h): a failed write leaves no file and replaces no file.
// Reads accept only the formats above, checked by extension and magic bytes before any decoder sees the file
// (so no other OpenImageIO reader parses untrusted files), and check the header's size against the limits
// below and against the file's size before decoding.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
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

// What an image is read for: each use has its formats and size limits (stated in content/README.md).
enum class ImageUse {
    Texture,      // PNG, JPEG; at most kMaxTextureSide per side and kMaxTexturePixels
    Environment,  // Radiance HDR, OpenEXR, PNG; at most kMaxEnvironmentSide per side and kMaxEnvironmentPixels
    Any,          // PNG, JPEG, HDR, EXR with the environment limits (tests, tools)
};
constexpr int kMaxTextureSide = 16384;
constexpr uint64_t kMaxTexturePixels = uint64_t(8192) * 8192;
constexpr int kMaxEnvironmentSide = 16384;
constexpr uint64_t kMaxEnvironmentPixels = uint64_t(16384) * 8192;
// Decoded bytes allowed per byte of file (deflate's ceiling is about 1032:1) plus a fixed allowance, so a
// 4 KB header cannot claim gigabytes.
constexpr uint64_t kMaxExpansionPerFileByte = 2048;
constexpr uint64_t kExpansionAllowance = uint64_t(16) << 20;

// Reads into floats (PNG/JPEG values in [0,1], sRGB-encoded as stored). Throws Error naming the file.
ImageF readImage(const std::filesystem::path& path, ImageUse use = ImageUse::Any);

// The image format of `bytes` by magic number ("png", "jpeg", "hdr", "openexr"), or "" when none of these.
std::string sniffImageFormat(const unsigned char* bytes, size_t size);
// Width and height from an in-memory PNG or JPEG header (no decoding); false when it cannot be read.
bool readImageHeader(const unsigned char* bytes, size_t size, int& width, int& height, int& channels);
// Throws Error("<what>: ...") when width x height exceeds the limits of `use` or what `fileBytes` can hold.
void checkImageSize(const std::string& what, int width, int height, int channels, int bytesPerChannel,
                    uint64_t fileBytes, ImageUse use);

// Throws UsageError naming --out when the path has no supported extension (.png or .exr).
enum class ImageFormat { Png, Exr };
ImageFormat imageFormatForPath(const std::filesystem::path& path, const char* flag);

}  // namespace glimmer
