// Resolution scale in the window: the controller (render/dynamic_resolution.h) converges into its dead band on a
// simulated frame-time model and then holds (no oscillation), ignores single slow frames, stops at its limits;
// frame-time percentiles are nearest-rank; the Catmull-Rom upscale reproduces constants and linear ramps; and
// end to end under xvfb, a 256x256 window at render scale 0.5 shows `glimmer render --size 128x128` upscaled by
// the same filter, with the UV derivatives (duvdx AOV) of the 128x128 render, twice those of a 256x256 one.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "core/frame_times.h"
#include "core/image_io.h"
#include "render/dynamic_resolution.h"
#include "render/image/upscale.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(UpscaleWindow, Window);

namespace glimmer {
namespace {
namespace fs = std::filesystem;

// Frame time = fixed part (geometry, UI) + part proportional to the pixel count, with +-5% noise.
struct FrameModel {
    double fixedMs, fullResMs;
    std::mt19937 rng{7};
    double operator()(float scale) {
        std::uniform_real_distribution<double> noise(0.95, 1.05);
        return (fixedMs + fullResMs * double(scale) * double(scale)) * noise(rng);
    }
};

TEST(DynamicResolution, ConvergesIntoTheDeadBandAndHolds) {
    for (auto [fixedMs, fullResMs] : {std::pair{20.0, 400.0}, std::pair{60.0, 150.0}, std::pair{5.0, 40.0}}) {
        SCOPED_TRACE(testing::Message() << fixedMs << " + " << fullResMs << " s^2 ms");
        FrameModel model{fixedMs, fullResMs};
        DynamicResolution control(1.0f, 12.0f);   // 83.3 ms
        const double targetMs = 1000.0 / 12.0;
        int changesLate = 0;
        for (int frame = 0; frame < 400; ++frame) {
            bool changed = control.addFrame(model(control.scale()));
            if (frame >= 200) changesLate += changed;
        }
        float s = control.scale();
        double settled = fixedMs + fullResMs * double(s) * double(s);
        if (s > DynamicResolution::kMinScale && s < DynamicResolution::kMaxScale) {
            // Inside the band, allowing the noise.
            EXPECT_LE(settled, targetMs * 1.05);
            EXPECT_GE(settled, targetMs * DynamicResolution::kRaiseBelow * 0.95);
        } else if (s == DynamicResolution::kMaxScale) {
            EXPECT_LE(settled, targetMs * 1.05) << "full resolution only when it is fast enough";
        }
        EXPECT_EQ(changesLate, 0) << "no oscillation once settled (scale " << s << ")";
    }
}

TEST(DynamicResolution, StepsAreBoundedAndLimitsHold) {
    DynamicResolution control(1.0f, 30.0f);
    float previous = control.scale();
    for (int frame = 0; frame < 200; ++frame) {
        control.addFrame(500.0);   // hopelessly slow: geometry-bound
        EXPECT_GE(control.scale(), previous * (1.0f - DynamicResolution::kMaxStep) - 1e-6f);
        previous = control.scale();
    }
    EXPECT_FLOAT_EQ(control.scale(), DynamicResolution::kMinScale);
    for (int frame = 0; frame < 200; ++frame) control.addFrame(1.0);
    EXPECT_FLOAT_EQ(control.scale(), DynamicResolution::kMaxScale);
    // A fixed scale never moves; sizes round and stay >= 1 pixel.
    DynamicResolution fixed(0.5f, 0.0f);
    for (int frame = 0; frame < 50; ++frame) EXPECT_FALSE(fixed.addFrame(1000.0));
    int w = 0, h = 0;
    fixed.internalSize(1280, 720, w, h);
    EXPECT_EQ(w, 640);
    EXPECT_EQ(h, 360);
    DynamicResolution(0.25f).internalSize(2, 1, w, h);
    EXPECT_EQ(w, 1);
    EXPECT_EQ(h, 1);
    EXPECT_FLOAT_EQ(DynamicResolution(0.01f).scale(), DynamicResolution::kMinScale);
}

TEST(DynamicResolution, OneSlowFrameDoesNotMoveTheScale) {
    DynamicResolution control(0.6f, 12.0f);
    for (int frame = 0; frame < 100; ++frame) {
        double ms = frame % 10 == 5 ? 400.0 : 75.0;   // in the band, with a hitch every 10 frames
        EXPECT_FALSE(control.addFrame(ms)) << "frame " << frame;
    }
    EXPECT_FLOAT_EQ(control.scale(), 0.6f);
}

TEST(FrameTimes, NearestRankPercentiles) {
    EXPECT_EQ(percentile({}, 0.5), 0.0);
    EXPECT_EQ(percentile({3.0}, 0.95), 3.0);
    std::vector<double> v;
    for (int i = 100; i >= 1; --i) v.push_back(double(i));
    EXPECT_EQ(percentile(v, 0.5), 50.0);
    EXPECT_EQ(percentile(v, 0.95), 95.0);
    EXPECT_EQ(percentile(v, 1.0), 100.0);
    EXPECT_EQ(percentile(v, 0.0), 1.0);
    FrameTimes times(10);
    for (int i = 1; i <= 30; ++i) times.add(double(i));
    EXPECT_EQ(times.all().size(), 30u);
    EXPECT_EQ(times.recentPercentile(0.0), 21.0) << "the ring keeps the last 10";
    EXPECT_EQ(times.recentPercentile(1.0), 30.0);
    EXPECT_EQ(times.runPercentile(0.5), 15.0);
}

TEST(Upscale, CatmullRomReproducesConstantsAndRamps) {
    const int w = 16, h = 8;
    std::vector<uint8_t> source(size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            uint8_t* p = &source[(size_t(y) * w + size_t(x)) * 4];
            p[0] = 90;                       // constant
            p[1] = uint8_t(10 + 12 * x);     // ramp along x
            p[2] = uint8_t(20 + 25 * y);     // ramp along y
            p[3] = 255;
        }
    std::vector<uint8_t> out = catmullRomUpscale(source, w, h, 2 * w, 2 * h);
    for (int y = 0; y < 2 * h; ++y)
        for (int x = 0; x < 2 * w; ++x) {
            const uint8_t* p = &out[(size_t(y) * 2 * w + size_t(x)) * 4];
            EXPECT_EQ(p[0], 90);
            // Away from the clamped border, a cubic that interpolates reproduces linear functions exactly.
            if (x >= 3 && x < 2 * w - 3) EXPECT_NEAR(p[1], 10.0 + 12.0 * ((x + 0.5) / 2.0 - 0.5), 0.51) << x;
            if (y >= 3 && y < 2 * h - 3) EXPECT_NEAR(p[2], 20.0 + 25.0 * ((y + 0.5) / 2.0 - 0.5), 0.51) << y;
            EXPECT_EQ(p[3], 255);
        }
    // Same size: identity.
    EXPECT_EQ(catmullRomUpscale(source, w, h, w, h)[4 * 5 + 1], source[4 * 5 + 1]);
}

std::vector<uint8_t> rgba8BottomUp(const ImageF& image) {
    std::vector<uint8_t> out;
    for (int y = image.height - 1; y >= 0; --y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 4; ++c)
                out.push_back(c < image.channels ? uint8_t(std::lround(image.at(x, y, c) * 255.0f)) : 255);
    return out;
}

TEST(UpscaleWindow, AtHalfScaleShowsTheHalfSizeRenderUpscaledWithItsDerivatives) {
    if (test::runUnderXvfb("command -v xvfb-run > /dev/null") != 0) GTEST_SKIP() << "xvfb-run not installed";
    std::string dir = test::makeTempDir("upscale");
    const std::string scene = " --scene plane25 --env none";
    fs::path view = dir + "/view.png", viewDuv = dir + "/view_duv.exr";
    fs::path small = dir + "/render128.png", smallDuv = dir + "/render128_duv.exr", fullDuv = dir + "/render256_duv.exr";
    std::string viewBase = std::string(GLIMMER_EXECUTABLE " view") + scene +
                           " --size 256x256 --render-scale 0.5 --target-fps 0 --like-render --hide-ui --frames 3"
                           " --screenshot ";
    ASSERT_EQ(test::runUnderXvfb(viewBase + view.string() + " > /dev/null 2>&1"), 0);
    ASSERT_EQ(test::runUnderXvfb(viewBase + viewDuv.string() + " --aov duvdx > /dev/null 2>&1"), 0);
    ASSERT_EQ(test::runGlimmer({"render", "--scene", "plane25", "--env", "none", "--size", "128x128", "--frames", "3",
                                "--out", small.string()}).exitCode, 0);
    for (auto [size, out] : {std::pair{"128x128", smallDuv}, std::pair{"256x256", fullDuv}})
        ASSERT_EQ(test::runGlimmer({"render", "--scene", "plane25", "--env", "none", "--size", size, "--frames", "3",
                                    "--aov", "duvdx", "--out", out.string()}).exitCode, 0);

    ImageF shown = readImage(view), rendered = readImage(small);
    ASSERT_EQ(shown.width, 256);
    ASSERT_EQ(rendered.width, 128);
    std::vector<uint8_t> expected = catmullRomUpscale(rgba8BottomUp(rendered), 128, 128, 256, 256);
    std::vector<uint8_t> actual = rgba8BottomUp(shown);
    size_t off = 0;
    int maxDiff = 0;
    for (size_t i = 0; i < actual.size(); ++i) {
        int d = std::abs(int(actual[i]) - int(expected[i]));
        maxDiff = std::max(maxDiff, d);
        off += d > 1;
    }
    EXPECT_LE(off, actual.size() / 1000) << "max difference " << maxDiff;

    // The window's G-buffer is the 128x128 one: same duvdx, and twice the 256x256 render's (a pixel covers twice
    // the UV span), compared on the 2x2 block means of the full-resolution image where the plane covers them.
    ImageF windowDuv = readImage(viewDuv), smallD = readImage(smallDuv), fullD = readImage(fullDuv);
    ASSERT_EQ(windowDuv.width, 128);
    size_t compared = 0, near = 0;
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x)
            for (int c = 0; c < 2; ++c) {
                float w = windowDuv.at(x, y, c), s = smallD.at(x, y, c);
                ASSERT_EQ(w, s) << x << "," << y;
                float block = 0.25f * (fullD.at(2 * x, 2 * y, c) + fullD.at(2 * x + 1, 2 * y, c) +
                                       fullD.at(2 * x, 2 * y + 1, c) + fullD.at(2 * x + 1, 2 * y + 1, c));
                if (std::abs(s) < 1e-6f || std::abs(block) < 1e-6f) continue;
                ++compared;
                near += std::abs(s - 2.0f * block) <= 0.05f * std::abs(s);
            }
    EXPECT_GT(compared, size_t(128 * 128 / 2));
    EXPECT_GE(double(near), 0.98 * double(compared));
}

// Issue 39: with lighting.glint_footprint=output a render pixel below scale 1 filters its glints over an output
// pixel's footprint: in a window at scale 0.5 the duvdx the glint method reads (its AOV, at the render size) is the
// render pixel's times 0.5, exactly, on every glinty pixel, where the default (render) leaves it alone; at scale 1
// the setting changes nothing.
TEST(UpscaleWindow, OutputGlintFootprintFiltersGlintsOverTheOutputPixel) {
    if (test::runUnderXvfb("command -v xvfb-run > /dev/null") != 0) GTEST_SKIP() << "xvfb-run not installed";
    std::string dir = test::makeTempDir("glint_footprint");
    auto windowDuv = [&](const std::string& footprint) {
        fs::path out = dir + "/duv_" + footprint + ".exr";
        std::string command = std::string(GLIMMER_EXECUTABLE " view") +
                              " --scene plane25 --env none --method deliot2023 --size 256x256 --render-scale 0.5"
                              " --target-fps 0 --like-render --hide-ui --frames 2 --aov duvdx"
                              " --set lighting.glint_footprint=" + footprint + " --screenshot " + out.string();
        EXPECT_EQ(test::runUnderXvfb(command + " > /dev/null 2>&1"), 0) << footprint;
        return readImage(out);
    };
    ImageF renderDuv = windowDuv("render"), outputDuv = windowDuv("output");
    ASSERT_EQ(renderDuv.width, 128);
    ASSERT_EQ(outputDuv.width, 128);
    size_t compared = 0, exact = 0;
    for (int y = 0; y < 128; ++y)
        for (int x = 0; x < 128; ++x)
            for (int c = 0; c < 2; ++c) {
                float r = renderDuv.at(x, y, c), o = outputDuv.at(x, y, c);
                if (std::abs(r) < 1e-7f) continue;
                ++compared;
                exact += o == 0.5f * r;
            }
    EXPECT_GT(compared, size_t(128 * 128 / 2));
    EXPECT_EQ(exact, compared) << "duvdx x 0.5 on every glinty pixel";
    // At scale 1 (offscreen, the same program) the setting changes nothing.
    auto full = [&](const std::string& footprint) {
        fs::path out = dir + "/full_" + footprint + ".exr";
        EXPECT_EQ(test::runGlimmer({"render", "--scene", "plane25", "--env", "none", "--method", "deliot2023",
                                    "--size", "64x64", "--set", "lighting.glint_footprint=" + footprint, "--out",
                                    out.string()}).exitCode, 0);
        return readImage(out);
    };
    EXPECT_EQ(full("render").pixels, full("output").pixels);
}

}  // namespace
}  // namespace glimmer
