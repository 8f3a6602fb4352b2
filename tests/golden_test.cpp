// Golden images of every built-in scene (smooth method, 256x256), and proof that the comparison catches a
// deliberately broken shader.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/files.h"
#include "offscreen/offscreen.h"
#include "scene/builtin_scenes.h"
#include "support/golden.h"
#include "support/process.h"

using namespace glimmer;

namespace {

RenderResult renderScene(const std::string& scene, const std::filesystem::path& shaderRoot = {}) {
    RenderRequest request;
    request.scene = scene;
    request.width = request.height = 256;
    request.shaderRoot = shaderRoot;
    request.environment = "none";   // goldens of the constant-ambient look; environment lighting: environment_test.cpp
    return renderOffscreen(request);
}

class BuiltinSceneGolden : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinSceneGolden, MatchesReference) {
    RenderResult result = renderScene(GetParam());
    EXPECT_EQ(result.stats["counts"]["non_finite_values"].get<size_t>(), 0u);
    test::GoldenComparison comparison =
        test::compareWithGolden("smooth_" + GetParam(), result.display, result.width, result.height);
    EXPECT_TRUE(comparison.passed) << comparison.message;
}

INSTANTIATE_TEST_SUITE_P(AllScenes, BuiltinSceneGolden, ::testing::ValuesIn(builtinSceneNames()));

// Copies shaders/ and replaces `from` by `to` in one file; returns the new root.
std::filesystem::path brokenShaderCopy(const std::string& name, const std::string& file, const std::string& from,
                                       const std::string& to) {
    std::filesystem::path root = std::filesystem::path(test::makeTempDir(name)) / "shaders";
    std::filesystem::copy(defaultShaderDir(), root, std::filesystem::copy_options::recursive);
    std::string text = readTextFile(root / file);
    size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from << " not found in " << file;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    std::ofstream(root / file, std::ios::trunc) << text;
    return root;
}

TEST(GoldenCompare, CatchesDroppedShadowing) {
    // Smith G = G1(wi) G1(wo) with the light's factor dropped: only the sphere's terminator changes.
    auto root = brokenShaderCopy("broken-shadowing", "common/brdf.glsl",
                                 "float G = G1_smooth(wi, alpha, ndf) * G1_smooth(wo, alpha, ndf);",
                                 "float G = G1_smooth(wo, alpha, ndf);");
    RenderResult result = renderScene("sphere", root);
    test::GoldenComparison comparison = test::compareWithGolden("smooth_sphere", result.display, 256, 256);
    if (comparison.updated) GTEST_SKIP() << "references are being rewritten";
    EXPECT_FALSE(comparison.passed) << "dropped shadowing passed the golden test: " << comparison.message;
}

TEST(GoldenCompare, CatchesABrokenNormalDistribution) {
    // GGX with alpha instead of alpha^2: a classic mistake.
    auto root = brokenShaderCopy("broken-ggx", "common/brdf.glsl", "float a2 = alpha * alpha;\n    float cos2 = h.z * h.z;\n    float d",
                                 "float a2 = alpha;\n    float cos2 = h.z * h.z;\n    float d");
    RenderResult result = renderScene("plane25", root);
    test::GoldenComparison comparison = test::compareWithGolden("smooth_plane25", result.display, 256, 256);
    if (comparison.updated) GTEST_SKIP() << "references are being rewritten";
    EXPECT_FALSE(comparison.passed) << "a broken GGX passed the golden test: " << comparison.message;
}

TEST(GoldenCompare, ToleratesOnePixelShiftsButNotTwo) {
    // A sparse synthetic sparkle pattern: shifted by one pixel it passes, by three it fails.
    const int w = 64, h = 64;
    auto pattern = [&](int shift) {
        std::vector<uint8_t> p(w * h * 4, 0);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                uint32_t hash = uint32_t(x + shift) * 73856093u ^ uint32_t(y) * 19349663u;
                hash = (hash ^ (hash >> 13)) * 0x5bd1e995u;
                bool on = (hash >> 16) % 50 == 0;  // sparse sparkles, 2% of pixels
                for (int c = 0; c < 3; ++c) p[(y * w + x) * 4 + c] = on ? 255 : 20;
                p[(y * w + x) * 4 + 3] = 255;
            }
        return p;
    };
    test::GoldenOptions options;
    options.blockThreshold = 1.0f;  // isolate the per-pixel rule
    EXPECT_TRUE(test::compareImages(pattern(0), pattern(1), w, h, options).passed);
    EXPECT_FALSE(test::compareImages(pattern(0), pattern(3), w, h, options).passed);
}

}  // namespace
