// Golden-image comparison for tests. References live in tests/golden/ref/<name>.png.
// A pixel fails when every reference pixel within `shiftRadius` differs from it by more than `channelThreshold`
// in some channel (glints are discontinuous in position: a one-pixel shift is not a regression); the image fails
// when the failing fraction exceeds `maxFailFraction`, or when 8x8 block means differ by more than
// `blockThreshold` (catches small global changes, e.g. a slightly wrong BRDF, that per-pixel thresholds miss).
// GLIMMER_UPDATE_GOLDEN=1 rewrites references. On failure new / reference / diff (x8) images are written to
// <build>/test-output/golden/ and the message says where.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glimmer::test {

struct GoldenOptions {
    float channelThreshold = 8.0f / 255.0f;
    double maxFailFraction = 0.002;
    int shiftRadius = 1;
    float blockThreshold = 2.0f / 255.0f;
};

struct GoldenComparison {
    bool passed = false;
    bool updated = false;     // the reference was (re)written
    double failFraction = 0.0;
    float maxBlockError = 0.0f;
    std::string message;
};

// `rgbaBottomUp`: 8-bit RGBA rows as read back from GL.
GoldenComparison compareWithGolden(const std::string& name, const std::vector<uint8_t>& rgbaBottomUp, int width,
                                   int height, const GoldenOptions& options = {});

// Same comparison between two in-memory images (no files), for tests that compare renders with each other.
GoldenComparison compareImages(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int width, int height,
                               const GoldenOptions& options = {});

// The reference <name>.png as 8-bit RGBA rows bottom-up (as compareImages takes them); empty when missing.
std::vector<uint8_t> readGolden(const std::string& name);

std::filesystem::path goldenReferenceDir();
std::filesystem::path testOutputDir();  // created on demand

}  // namespace glimmer::test
