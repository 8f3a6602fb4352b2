// The first minute of `glimmer view` (issue 39): the window's first frames are loading frames drawn while the
// start-up runs (app/walkthrough/loading_screen.h): not black, with the scene's title, the step in progress in
// text and a progress bar that grows, and the start-up times in the log. Skipped where xvfb-run is absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "support/process.h"
#include "support/test_needs.h"

GLIMMER_SUITE_NEEDS(WindowStartup, Window);

namespace glimmer {
namespace {
namespace fs = std::filesystem;

bool haveXvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

// Pixels within 3 (8-bit units) of `rgb`.
size_t countColour(const ImageF& image, int r, int g, int b) {
    size_t n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (std::abs(image.at(x, y, 0) * 255.0f - float(r)) <= 3.0f &&
                std::abs(image.at(x, y, 1) * 255.0f - float(g)) <= 3.0f &&
                std::abs(image.at(x, y, 2) * 255.0f - float(b)) <= 3.0f)
                ++n;
    return n;
}

TEST(WindowStartup, LoadingFramesShowProgressTextBeforeTheFirstPicture) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    const fs::path dir = test::makeTempDir("loading-frames");
    const fs::path log = dir / "log.txt", shot = dir / "picture.png";
    ASSERT_EQ(test::runUnderXvfb("GLIMMER_LOADING_SCREENSHOTS=" + dir.string() + " " GLIMMER_EXECUTABLE
                                 " view --scene plane90 --size 640x360 --frames 1 --hide-ui --screenshot " +
                                 shot.string() + " > " + log.string() + " 2>&1"),
              0);
    std::vector<fs::path> frames;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().filename().string().rfind("loading-", 0) == 0) frames.push_back(entry.path());
    std::sort(frames.begin(), frames.end());
    // At least: shaders, collision, environment, the first picture.
    ASSERT_GE(frames.size(), 4u);
    size_t previousBar = 0;
    for (const fs::path& file : frames) {
        const ImageF frame = readImage(file);
        ASSERT_EQ(frame.width, 640);
        ASSERT_EQ(frame.height, 360);
        double mean = 0.0;
        for (float v : frame.pixels) mean += v;
        mean /= double(frame.pixels.size());
        EXPECT_GT(mean, 0.08) << file << ": the loading frame is (nearly) black";
        // The title (heading colour), the step in progress (text colour), the progress bar's fill.
        EXPECT_GT(countColour(frame, 255, 204, 120), 300u) << file << ": no title";
        EXPECT_GT(countColour(frame, 232, 232, 236), 100u) << file << ": no step in progress";
        const size_t bar = countColour(frame, 62, 104, 168);
        if (file != frames.front()) EXPECT_GT(bar, previousBar) << file << ": the progress bar did not grow";
        previousBar = bar;
    }
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_NE(text.str().find("view: loading frame at "), std::string::npos) << text.str();
    EXPECT_NE(text.str().find("view: first picture at "), std::string::npos) << text.str();
    EXPECT_NE(text.str().find("view: loading: building the shaders "), std::string::npos) << text.str();
}

}  // namespace
}  // namespace glimmer
