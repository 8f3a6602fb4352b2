// `glimmer view` end to end under xvfb-run: with --hide-ui the window's screenshot equals `glimmer render` of the
// same scene, camera and size; with the UI the panel is drawn (differs from the picture, matches a reference
// crop) and the stats strip is there. Skipped where xvfb-run is absent.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/image_io.h"
#include "support/golden.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(Window, Window);

namespace glimmer {
namespace {
namespace fs = std::filesystem;

int run(const std::string& command) {
    int status = std::system((command + " > /dev/null 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool haveXvfb() { return run("command -v xvfb-run") == 0; }

fs::path outputDir() {
    fs::path dir = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "window";
    fs::create_directories(dir);
    return dir;
}

// Fraction of pixels in the rectangle whose channels differ by more than `threshold` (8-bit units).
double differingFraction(const ImageF& a, const ImageF& b, int x0, int y0, int x1, int y1, float threshold) {
    size_t differ = 0, total = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++total)
            for (int c = 0; c < 3; ++c)
                if (std::abs(a.at(x, y, c) - b.at(x, y, c)) * 255.0f > threshold) { ++differ; break; }
    return total ? double(differ) / double(total) : 0.0;
}

// The rectangle as 8-bit RGBA rows, bottom row first (what test::compareWithGolden takes).
std::vector<uint8_t> cropRgba8BottomUp(const ImageF& image, int x0, int y0, int x1, int y1) {
    std::vector<uint8_t> out;
    for (int y = y1 - 1; y >= y0; --y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 4; ++c)
                out.push_back(c < image.channels ? uint8_t(std::lround(image.at(x, y, c) * 255.0f)) : 255);
    return out;
}

void expectWindowEqualsRender(const std::string& name, const std::string& sceneArgs, int width, int height) {
    fs::path dir = outputDir();
    std::string size = std::to_string(width) + "x" + std::to_string(height);
    fs::path windowShot = dir / (name + "_view.png"), rendered = dir / (name + "_render.png");
    ASSERT_EQ(test::runUnderXvfb(std::string(GLIMMER_EXECUTABLE " view ") + sceneArgs + " --size " + size +
                                 " --frames 3 --like-render --hide-ui --screenshot " + windowShot.string() + " > /dev/null 2>&1"),
              0);
    ASSERT_EQ(run(std::string(GLIMMER_EXECUTABLE) + " render " + sceneArgs + " --size " + size +
                  " --frames 3 --out " + rendered.string()), 0);
    ImageF a = readImage(windowShot), b = readImage(rendered);
    ASSERT_EQ(a.width, width);
    ASSERT_EQ(a.height, height);
    ASSERT_EQ(b.width, width);
    // Same renderer, same camera, same llvmpipe: the images agree to the bit here; the tolerance only allows for
    // a CPU-feature difference between the two processes.
    EXPECT_LE(differingFraction(a, b, 0, 0, width, height, 1.0f), 0.001) << windowShot << " vs " << rendered;
    test::GoldenComparison same = test::compareImages(cropRgba8BottomUp(a, 0, 0, width, height),
                                                      cropRgba8BottomUp(b, 0, 0, width, height), width, height);
    EXPECT_TRUE(same.passed) << same.message;
}

TEST(Window, HiddenUiScreenshotEqualsGlimmerRender) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    expectWindowEqualsRender("sphere", "--scene sphere --method smooth", 320, 240);
    expectWindowEqualsRender("plane25", "--scene plane25 --method smooth --set material.alpha=0.1 --set exposure=0.5", 320, 240);
}

TEST(Window, UiPanelAndStatsAreDrawnOverThePicture) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    fs::path dir = outputDir();
    fs::path withUi = dir / "ui.png", withoutUi = dir / "noui.png";
    std::string common =
        GLIMMER_EXECUTABLE " view --scene sphere --method smooth --size 1280x720 --frames 3 --like-render ";
    ASSERT_EQ(test::runUnderXvfb(common + "--screenshot " + withUi.string() + " > /dev/null 2>&1"), 0);
    ASSERT_EQ(test::runUnderXvfb(common + "--hide-ui --screenshot " + withoutUi.string() + " > /dev/null 2>&1"), 0);
    ImageF ui = readImage(withUi), plain = readImage(withoutUi);
    ASSERT_EQ(ui.width, 1280);
    ASSERT_EQ(ui.height, 720);

    // The top of the panel (title, method selector, method title, debug-view selector) at UI scale 2. Lower
    // rows depend on the method and parameter tables, and the stats strip on timings, so they stay out.
    const int x0 = 8, y0 = 8, x1 = 432, y1 = 140;
    EXPECT_GT(differingFraction(ui, plain, x0, y0, x1, y1, 8.0f), 0.5) << "no panel drawn";
    EXPECT_GT(differingFraction(ui, plain, 0, 665, 1280, 720, 8.0f), 0.3) << "no stats strip drawn";
    EXPECT_LT(differingFraction(ui, plain, 700, 100, 1000, 600, 0.0f), 1e-9) << "UI drawn over the picture";

    test::GoldenComparison golden =
        test::compareWithGolden("view_panel_top", cropRgba8BottomUp(ui, x0, y0, x1, y1), x1 - x0, y1 - y0);
    if (golden.updated) GTEST_SKIP() << golden.message;
    EXPECT_TRUE(golden.passed) << golden.message;
}

// Headless runs (--frames) do not watch shaders: a compile error fails the run with file:line.
TEST(Window, BrokenShaderFailsAFramesRunWithFileAndLine) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    fs::path dir = outputDir() / "broken-shaders";
    fs::remove_all(dir);
    fs::copy(fs::path(GLIMMER_SOURCE_DIR) / "shaders", dir, fs::copy_options::recursive);
    {
        std::ofstream out(dir / "image/tonemap.frag", std::ios::app);
        out << "\nthis is not glsl;\n";
    }
    fs::path errors = outputDir() / "broken-shaders.err";
    int code = test::runUnderXvfb(GLIMMER_EXECUTABLE " view --scene sphere --size 64x64 --frames 1 --shader-dir " + dir.string() +
                                  " --screenshot " + (outputDir() / "never.png").string() + " > /dev/null 2> " +
                                  errors.string());
    EXPECT_EQ(code, 1);
    std::ifstream in(errors);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("tonemap.frag:"), std::string::npos) << text;
}

TEST(Window, BadArgumentsFailWithAClearMessage) {
    // Argument errors are reported before any window is opened: no display needed.
    EXPECT_EQ(run(std::string(GLIMMER_EXECUTABLE) + " view --screenshot x.png"), 2);
    EXPECT_EQ(run(std::string(GLIMMER_EXECUTABLE) + " view --frames 1 --screenshot x.txt"), 2);
    EXPECT_EQ(run(std::string(GLIMMER_EXECUTABLE) + " view --frames -1"), 2);
    EXPECT_EQ(run(std::string(GLIMMER_EXECUTABLE) + " view --method nope"), 2);
}

}  // namespace
}  // namespace glimmer
