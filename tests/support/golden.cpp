#include "support/golden.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/image_io.h"

namespace glimmer::test {

std::filesystem::path goldenReferenceDir() { return std::filesystem::path(GLIMMER_TEST_DIR) / "golden" / "ref"; }

std::filesystem::path testOutputDir() {
    std::filesystem::path dir(GLIMMER_TEST_OUTPUT_DIR);
    std::filesystem::create_directories(dir);
    return dir;
}

GoldenComparison compareImages(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int width, int height,
                               const GoldenOptions& options) {
    GoldenComparison result;
    if (a.size() != b.size() || a.size() != size_t(width) * height * 4) {
        result.message = "image sizes differ";
        return result;
    }
    const int threshold = int(std::ceil(options.channelThreshold * 255.0f));
    auto pixelClose = [&](int x, int y, int rx, int ry) {
        const uint8_t* p = &a[(size_t(y) * width + x) * 4];
        const uint8_t* q = &b[(size_t(ry) * width + rx) * 4];
        for (int c = 0; c < 3; ++c)
            if (std::abs(int(p[c]) - int(q[c])) > threshold) return false;
        return true;
    };
    size_t failing = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            bool matched = false;
            for (int dy = -options.shiftRadius; dy <= options.shiftRadius && !matched; ++dy)
                for (int dx = -options.shiftRadius; dx <= options.shiftRadius && !matched; ++dx) {
                    int rx = x + dx, ry = y + dy;
                    if (rx >= 0 && ry >= 0 && rx < width && ry < height) matched = pixelClose(x, y, rx, ry);
                }
            failing += !matched;
        }
    // 8x8 block means: small systematic errors.
    float maxBlock = 0.0f;
    for (int by = 0; by < height; by += 8)
        for (int bx = 0; bx < width; bx += 8) {
            double sum[3] = {0, 0, 0};
            int n = 0;
            for (int y = by; y < std::min(by + 8, height); ++y)
                for (int x = bx; x < std::min(bx + 8, width); ++x, ++n)
                    for (int c = 0; c < 3; ++c)
                        sum[c] += double(a[(size_t(y) * width + x) * 4 + c]) - double(b[(size_t(y) * width + x) * 4 + c]);
            for (int c = 0; c < 3; ++c) maxBlock = std::max(maxBlock, float(std::abs(sum[c]) / n / 255.0));
        }
    result.failFraction = double(failing) / (double(width) * height);
    result.maxBlockError = maxBlock;
    result.passed = result.failFraction <= options.maxFailFraction && maxBlock <= options.blockThreshold;
    std::ostringstream message;
    message << "failing pixels " << result.failFraction * 100.0 << "% (limit " << options.maxFailFraction * 100.0
            << "%), max 8x8 block error " << maxBlock * 255.0f << "/255 (limit " << options.blockThreshold * 255.0f
            << "/255)";
    result.message = message.str();
    return result;
}

static std::vector<uint8_t> toBottomUpRgba8(const ImageF& image) {
    std::vector<uint8_t> out(size_t(image.width) * image.height * 4, 255);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < std::min(image.channels, 4); ++c)
                out[(size_t(image.height - 1 - y) * image.width + x) * 4 + c] =
                    uint8_t(std::clamp(image.at(x, y, c), 0.0f, 1.0f) * 255.0f + 0.5f);
    return out;
}

static std::filesystem::path referencePath(const std::string& name) { return goldenReferenceDir() / (name + ".png"); }

std::vector<uint8_t> readGolden(const std::string& name) {
    std::filesystem::path reference = referencePath(name);
    if (!std::filesystem::exists(reference)) return {};
    return toBottomUpRgba8(readImage(reference));
}

GoldenComparison compareWithGolden(const std::string& name, const std::vector<uint8_t>& rgba, int width, int height,
                                   const GoldenOptions& options) {
    std::filesystem::path reference = referencePath(name);
    const char* update = std::getenv("GLIMMER_UPDATE_GOLDEN");
    if (update && update[0] == '1') {
        std::filesystem::create_directories(reference.parent_path());
        writePng(reference, rgba.data(), width, height);
        GoldenComparison result;
        result.passed = result.updated = true;
        result.message = "reference rewritten: " + reference.string();
        return result;
    }
    if (!std::filesystem::exists(reference)) {
        GoldenComparison result;
        result.message = "GOLDEN_MISSING: " + reference.string() + " (run with GLIMMER_UPDATE_GOLDEN=1 to create it)";
        return result;
    }
    ImageF refImage = readImage(reference);
    if (refImage.width != width || refImage.height != height) {
        GoldenComparison result;
        result.message = reference.string() + ": size differs from the render";
        return result;
    }
    std::vector<uint8_t> refPixels = toBottomUpRgba8(refImage);
    GoldenComparison result = compareImages(rgba, refPixels, width, height, options);
    if (!result.passed) {
        std::filesystem::path dir = testOutputDir() / "golden";
        std::filesystem::create_directories(dir);
        writePng(dir / (name + ".new.png"), rgba.data(), width, height);
        writePng(dir / (name + ".ref.png"), refPixels.data(), width, height);
        std::vector<uint8_t> diff(rgba.size(), 255);
        for (size_t i = 0; i < rgba.size(); ++i)
            if (i % 4 != 3) diff[i] = uint8_t(std::min(255, 8 * std::abs(int(rgba[i]) - int(refPixels[i]))));
        writePng(dir / (name + ".diff.png"), diff.data(), width, height);
        result.message = name + ": " + result.message + "; new/ref/diff images in " + dir.string();
    }
    return result;
}

}  // namespace glimmer::test
