// TAA upsampling (TAAU; docs/image.md "TAA upsampling"): aa=taa at render_scale < 1 resolves the internal frames
// directly to the output size. Tested against what it replaces, the Catmull-Rom upscale of the no-AA render:
//   (a) edges: RMSE of the display image on geometric edges against a 4x4 supersampled reference at the output
//       size, still camera, render_scale 0.5;
//   (b) glints: over the glint pixels of plane25, the fraction of bright pixels and p99.9 / mean of the HDR
//       luminance, TAAU within 15% of the upscaled no-AA render at the same render scale (the glint footprints are
//       those of the internal pixel in both: a native-resolution render has other glints by construction);
//   (c) no NaN / Inf in any image;
//   (d) a render-scale change mid-sequence keeps the history (no reset) and the image (mean luminance);
//   (e) the window at render_scale 0.5 with aa=taa shows the TAAU image (not the Catmull-Rom upscale);
//   (f) taa.upsample=0 gives exactly the Catmull-Rom upscale of the TAA render at the internal size.
// With GLIMMER_IMAGE_MEASURE=1 the edge test also prints the table of docs/image.md (render_scale 0.5 and 0.25,
// no-AA + upscale, TAA at the internal size + upscale, TAAU) and the pass costs at 640x360.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/clock.h"
#include "core/files.h"
#include "core/image_io.h"
#include "offscreen/offscreen.h"
#include "render/aov.h"
#include "render/image/halton_jitter.h"
#include "render/image/upscale.h"
#include "scene/scene_loader.h"
#include "support/measure.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(ImageTaau, GlContext);
GLIMMER_SUITE_NEEDS(Window, Window);

namespace glimmer {
namespace {

// GLIMMER_MEASURE=1 (tests/support/measure.h), or its older name GLIMMER_IMAGE_MEASURE=1 that docs/image.md uses.
bool measureRun() {
    const char* v = std::getenv("GLIMMER_IMAGE_MEASURE");
    return test::fullMeasurement() || (v && std::string(v) == "1");
}

size_t nonFinite(const RenderResult& r) {
    size_t n = 0;
    for (float v : r.hdr) n += !std::isfinite(v);
    return n;
}

// Pixels next to a depth discontinuity (> 5% relative, 4-neighbourhood) of the full-size depth AOV, sky included.
std::vector<uint8_t> edgeMask(OffscreenSession& session, RenderRequest request) {
    request.settings.debugView = findAov("depth").viewId;
    request.renderScale = 1.0f;
    request.frames = 1;
    RenderResult depth = session.render(request);
    const int w = request.width, h = request.height;
    auto d = [&](int x, int y) {
        size_t i = (size_t(y) * w + x) * 4;
        return depth.hdr[i + 3] > 0.0f ? depth.hdr[i] : 1e6f;
    };
    std::vector<uint8_t> mask(size_t(w) * h, 0);
    for (int y = 1; y < h - 1; ++y)
        for (int x = 1; x < w - 1; ++x) {
            float c = d(x, y);
            for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
                if (std::abs(d(x + dx, y + dy) - c) > 0.05f * std::min(c, d(x + dx, y + dy))) mask[size_t(y) * w + x] = 1;
        }
    return mask;
}

double maskedRmse(const RenderResult& a, const RenderResult& b, const std::vector<uint8_t>& mask) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        for (int k = 0; k < 3; ++k) {
            double e = (double(a.display[i * 4 + k]) - double(b.display[i * 4 + k])) / 255.0;
            sum += e * e;
        }
        n += 3;
    }
    return n ? std::sqrt(sum / double(n)) : 0.0;
}

double meanLuminance(const RenderResult& r) {
    double sum = 0.0;
    size_t n = r.hdr.size() / 4;
    for (size_t i = 0; i < n; ++i) sum += 0.2126 * r.hdr[i * 4] + 0.7152 * r.hdr[i * 4 + 1] + 0.0722 * r.hdr[i * 4 + 2];
    return sum / double(n);
}

RenderRequest atriumRequest(int width, int height) {
    RenderRequest request;
    request.scene = "atrium";
    request.camera = "entrance";
    request.width = width;
    request.height = height;
    request.settings.method = "smooth";
    // Edges and history do not depend on them, and the probes' capture and the shadow maps' first frame would cost
    // seconds of CI time.
    request.settings.apply("probes.enabled=0");
    request.settings.apply("shadow.enabled=0");
    return request;
}

// The edge errors of one render scale: no AA + Catmull-Rom upscale, TAA at the internal size + the same upscale
// (what the window did before TAAU), and TAAU.
struct EdgeErrors {
    double noAa = 0, taaThenUpscale = 0, taau = 0;
};
EdgeErrors edgeErrors(OffscreenSession& session, const RenderRequest& request, const RenderResult& reference,
                      const std::vector<uint8_t>& mask, float scale, int frames, bool withTaaThenUpscale) {
    RenderRequest plain = request;
    plain.renderScale = scale;
    RenderResult noAa = session.render(plain);
    // TAA at the internal size, then the spatial upscale: render the internal size itself with aa=taa, upscale.
    RenderRequest internal = plain;
    internal.renderScale = 1.0f;
    internal.width = std::max(1, int(std::lround(scale * float(request.width))));
    internal.height = std::max(1, int(std::lround(scale * float(request.height))));
    internal.settings.apply("aa=taa");
    internal.frames = frames;
    RenderResult taaSmall, taaUpscaled;
    if (withTaaThenUpscale) {
        taaSmall = session.render(internal);
        taaUpscaled.display = catmullRomUpscale(taaSmall.display, internal.width, internal.height, request.width,
                                                request.height);
    }
    RenderRequest upsampled = plain;
    upsampled.settings.apply("aa=taa");
    upsampled.frames = frames;
    RenderResult taau = session.render(upsampled);
    EXPECT_EQ(taau.stats["upscale"], "taa");
    EXPECT_EQ(noAa.stats["upscale"], "catmull-rom");
    EXPECT_EQ(nonFinite(noAa) + nonFinite(taaSmall) + nonFinite(taau), 0u);
    EdgeErrors e;
    e.noAa = maskedRmse(noAa, reference, mask);
    e.taaThenUpscale = withTaaThenUpscale ? maskedRmse(taaUpscaled, reference, mask) : 0.0;
    e.taau = maskedRmse(taau, reference, mask);
    std::printf("  render_scale %.2f (%dx%d -> %dx%d), %d frames: edge RMSE vs 4x4 SSAA: no AA + upscale %.4f, "
                "TAA + upscale %s, TAAU %.4f (TAAU / no AA %.2f)\n",
                double(scale), internal.width, internal.height, request.width, request.height, frames, e.noAa,
                withTaaThenUpscale ? std::to_string(e.taaThenUpscale).c_str() : "(measurement runs)", e.taau,
                e.taau / e.noAa);
    return e;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// Wall ms (glFinish after each pass, llvmpipe) of the passes `names` over `runs` further frames of `request`
// (the history continues between them), median per pass.
std::vector<double> passMs(OffscreenSession& session, RenderRequest request, const std::vector<std::string>& names,
                           int runs) {
    std::vector<std::vector<double>> samples(names.size());
    request.frames = 1;
    for (int r = 0; r < runs; ++r) {
        RenderResult result = session.render(request);
        for (const auto& pass : result.stats["passes"])
            for (size_t i = 0; i < names.size(); ++i)
                if (pass["name"] == names[i]) samples[i].push_back(pass["wall_ms"].get<double>());
    }
    std::vector<double> out;
    for (auto& s : samples) out.push_back(median(s));
    return out;
}

// docs/image.md's cost table, side by side in one run: the TAA pass at the internal size followed by the
// Catmull-Rom upscale (GPU pass of the window) against the TAAU pass, and the tone mapping at each size.
void printPassCosts(OffscreenSession& session, const RenderRequest& request, float scale) {
    RenderRequest internal = request;
    internal.width = int(std::lround(scale * float(request.width)));
    internal.height = int(std::lround(scale * float(request.height)));
    internal.settings.apply("aa=taa");
    internal.frames = 8;
    session.render(internal);
    std::vector<double> small = passMs(session, internal, {"taa", "tonemap", "lighting", "gbuffer"}, 7);
    // The window's upscale pass on the internal TAA image, timed the same way.
    session.context().makeCurrent();
    UpscalePass upscale(defaultShaderDir());
    gl::Texture target = gl::createTexture2D(GL_RGBA8, request.width, request.height);
    gl::Framebuffer fbo = gl::createFramebuffer("upscale target", {target.id()});
    const Renderer& renderer = session.renderer();
    std::vector<double> upscaleMs;
    for (int r = 0; r < 7; ++r) {
        glFinish();
        Stopwatch clock;
        upscale.draw(renderer.displayTexture(), renderer.displayFramebuffer(), renderer.lastView().postWidth,
                     renderer.lastView().postHeight, fbo.id(), request.width, request.height);
        glFinish();
        upscaleMs.push_back(clock.elapsedMs());
    }
    RenderRequest upsampled = request;
    upsampled.renderScale = scale;
    upsampled.settings.apply("aa=taa");
    upsampled.frames = 8;
    session.render(upsampled);
    std::vector<double> taau = passMs(session, upsampled, {"taa", "tonemap", "lighting", "gbuffer"}, 7);
    std::printf("  pass wall ms at render_scale %.2f (%dx%d -> %dx%d), median of 7: TAA %.2f + upscale %.2f + tonemap "
                "%.2f = %.2f | TAAU %.2f + tonemap %.2f = %.2f | (lighting %.2f, gbuffer %.2f)\n",
                double(scale), internal.width, internal.height, request.width, request.height, small[0],
                median(upscaleMs), small[1], small[0] + median(upscaleMs) + small[1], taau[0], taau[1],
                taau[0] + taau[1], taau[2], taau[3]);
}

// (d) Right after a TAAU sequence at render_scale 0.5: two frames at 0.35, then one at 1 (the plain resolve on the
// same output-size history). Neither may reset the history or change the mean luminance by more than 3%.
void expectScaleChangesKeepTheHistory(OffscreenSession& session, const RenderRequest& request) {
    RenderRequest at = request;
    at.settings.apply("aa=taa");
    at.renderScale = 0.5f;
    at.frames = 1;
    RenderResult before = session.render(at);
    const unsigned resets = session.renderer().taaResets(), frames = session.renderer().taaFrames();
    ASSERT_GT(frames, 8u) << "the TAAU sequence before must still be accumulating";
    at.renderScale = 0.35f;
    at.frames = 2;
    RenderResult smaller = session.render(at);
    EXPECT_EQ(session.renderer().taaResets(), resets) << "a render-scale change must not reset the history";
    EXPECT_EQ(session.renderer().taaFrames(), frames + 2);
    EXPECT_EQ(smaller.stats["upscale"], "taa");
    at.renderScale = 1.0f;
    at.frames = 1;
    RenderResult native = session.render(at);
    EXPECT_EQ(session.renderer().taaResets(), resets) << "nor a change back to the output size";
    EXPECT_EQ(native.stats["upscale"], "none");
    EXPECT_EQ(nonFinite(before) + nonFinite(smaller) + nonFinite(native), 0u);
    double a = meanLuminance(before), b = meanLuminance(smaller), c = meanLuminance(native);
    std::printf("  mean luminance: scale 0.5 %.4f, then 0.35 %.4f (x%.4f), then 1 %.4f (x%.4f)\n", a, b, b / a, c, c / a);
    EXPECT_GT(a, 0.01);
    EXPECT_NEAR(b / a, 1.0, 0.03);
    EXPECT_NEAR(c / a, 1.0, 0.03);
}

TEST(ImageTaau, EdgesBeatTheSpatialUpscaleAndScaleChangesKeepTheHistory) {
    const bool full = measureRun();
    RenderRequest request = full ? atriumRequest(640, 360) : atriumRequest(192, 108);
    OffscreenSession session(request);
    std::vector<uint8_t> mask = edgeMask(session, request);
    size_t edges = 0;
    for (uint8_t m : mask) edges += m;
    ASSERT_GT(edges, mask.size() / 100);
    RenderRequest ssaa = request;
    ssaa.settings.apply("aa=ssaa");
    ssaa.settings.apply("ssaa.factor=4");
    RenderResult reference = session.render(ssaa);
    EdgeErrors half = edgeErrors(session, request, reference, mask, 0.5f, 32, full);
    EXPECT_LT(half.taau, 0.85 * half.noAa);
    expectScaleChangesKeepTheHistory(session, request);
    if (!full) return;
    edgeErrors(session, request, reference, mask, 0.25f, 128, true);
    printPassCosts(session, request, 0.5f);
    printPassCosts(session, request, 0.25f);
}

double meanAbsDisplayDiff(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += std::abs(double(a[i]) - double(b[i]));
    return a.empty() ? 0.0 : sum / double(a.size());
}

// taa.upsample=0 (the window's default on software renderers): TAA and the post passes at the render size, then
// the Catmull-Rom upscale. The image must be the upscale of the TAA render at the internal size (same frames, each
// from a reset history), and must differ from the TAAU image (so the comparison can fail).
TEST(ImageTaau, UpsampleOffResolvesAtTheRenderSizeThenUpscales) {
    RenderRequest request = atriumRequest(192, 108);
    OffscreenSession session(request);
    RenderRequest internal = request;
    internal.width = 96;
    internal.height = 54;
    internal.settings.apply("aa=taa");
    internal.frames = 8;
    session.renderer().resetHistory();
    RenderResult small = session.render(internal);
    ASSERT_EQ(small.stats["upscale"], "none");
    const std::vector<uint8_t> expected = catmullRomUpscale(small.display, 96, 54, 192, 108);

    RenderRequest off = request;
    off.renderScale = 0.5f;
    off.settings.apply("aa=taa");
    off.settings.apply("taa.upsample=0");
    off.frames = 8;
    session.renderer().resetHistory();
    RenderResult resolvedSmall = session.render(off);
    EXPECT_EQ(resolvedSmall.stats["upscale"], "catmull-rom");
    EXPECT_EQ(session.renderer().lastView().postWidth, 96) << "the post passes must run at the render size";

    RenderRequest on = off;
    on.settings.apply("taa.upsample=1");
    session.renderer().resetHistory();
    RenderResult taau = session.render(on);
    EXPECT_EQ(taau.stats["upscale"], "taa");
    EXPECT_EQ(nonFinite(small) + nonFinite(resolvedSmall) + nonFinite(taau), 0u);

    const double offError = meanAbsDisplayDiff(resolvedSmall.display, expected);
    const double taauError = meanAbsDisplayDiff(taau.display, expected);
    std::printf("  mean |display - upscale(TAA at 96x54)| (8-bit): taa.upsample=0 %.3f, TAAU %.3f\n", offError,
                taauError);
    // Measured: 0 (bit-identical on llvmpipe) and 1.7.
    EXPECT_LT(offError, 0.05);
    EXPECT_GT(taauError, 0.5);
}

// Over the glint pixels: bright = above the upscaled no-AA image's 99th percentile of the same pixels.
struct SparkleStats {
    double brightFraction = 0.0, p999OverMean = 0.0;
};
std::vector<double> maskedLuminance(const RenderResult& r, const std::vector<uint8_t>& mask) {
    std::vector<double> l;
    for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i]) l.push_back(0.2126 * r.hdr[i * 4] + 0.7152 * r.hdr[i * 4 + 1] + 0.0722 * r.hdr[i * 4 + 2]);
    return l;
}
double percentile(std::vector<double> l, double q) {
    size_t k = size_t(q * double(l.size() - 1));
    std::nth_element(l.begin(), l.begin() + std::ptrdiff_t(k), l.end());
    return l[k];
}
SparkleStats sparkleStats(const RenderResult& r, const std::vector<uint8_t>& mask, double threshold) {
    std::vector<double> l = maskedLuminance(r, mask);
    double mean = 0.0;
    size_t bright = 0;
    for (double v : l) mean += v / double(l.size()), bright += v > threshold;
    return {double(bright) / double(l.size()), percentile(l, 0.999) / mean};
}

TEST(ImageTaau, KeepsTheGlintsOfPlane25) {
    RenderRequest request;
    request.scene = "plane25";
    request.camera = "grazing";
    request.width = 256;
    request.height = 144;
    request.settings.method = "deliot2023";
    OffscreenSession session(request);
    RenderRequest ids = request;
    ids.settings.debugView = findAov("material").viewId;
    RenderResult material = session.render(ids);
    Scene scene = loadScene(request.scene);
    std::vector<uint8_t> mask(size_t(request.width) * request.height, 0);
    for (size_t i = 0; i < mask.size(); ++i) {
        size_t id = size_t(std::lround(material.hdr[i * 4 + 2]));
        mask[i] = material.hdr[i * 4 + 3] > 0.0f && id < scene.materials.size() && scene.materials[id].glinty;
    }
    size_t pixels = 0;
    for (uint8_t m : mask) pixels += m;
    ASSERT_GT(pixels, mask.size() / 50) << "the view must show the glint material";

    RenderRequest plain = request;
    plain.renderScale = 0.5f;
    RenderResult upscaled = session.render(plain);
    RenderRequest taau = plain;
    taau.settings.apply("aa=taa");
    taau.frames = 32;
    RenderResult resolved = session.render(taau);
    ASSERT_EQ(resolved.stats["upscale"], "taa");
    EXPECT_EQ(nonFinite(upscaled) + nonFinite(resolved), 0u);
    double threshold = percentile(maskedLuminance(upscaled, mask), 0.99);
    SparkleStats a = sparkleStats(upscaled, mask, threshold), b = sparkleStats(resolved, mask, threshold);
    // For the record (measurement runs): against the native-size no-AA render (other footprints, other glints).
    SparkleStats n;
    double nativeThreshold = 0.0;
    if (measureRun()) {
        RenderResult native = session.render(request);
        nativeThreshold = percentile(maskedLuminance(native, mask), 0.99);
        n = sparkleStats(native, mask, nativeThreshold);
    }
    std::printf("  plane25 glints (%zu pixels, %dx%d from %dx%d): bright fraction %.5f -> %.5f (x%.3f), "
                "p99.9/mean %.2f -> %.2f (x%.3f)\n",
                pixels, request.width, request.height, request.width / 2, request.height / 2, a.brightFraction,
                b.brightFraction, b.brightFraction / a.brightFraction, a.p999OverMean, b.p999OverMean,
                b.p999OverMean / a.p999OverMean);
    if (measureRun())
        std::printf("  native-size no AA: p99.9/mean %.2f; TAAU bright fraction over the native 99th percentile %.5f\n",
                    n.p999OverMean, sparkleStats(resolved, mask, nativeThreshold).brightFraction);
    ASSERT_GT(a.brightFraction, 0.0);
    EXPECT_NEAR(b.brightFraction / a.brightFraction, 1.0, 0.15);
    EXPECT_NEAR(b.p999OverMean / a.p999OverMean, 1.0, 0.15);
}


// (e) The window's path (renderer -> display at the window size -> present -> screenshot) shows exactly what the
// offscreen TAAU render of the same frames gives, and that differs from the spatial upscale of the no-AA render
// (so the comparison can fail). plane25 at 128x128 (the window's camera equals the scene camera there).
TEST(Window, TaaAtHalfScaleShowsTheTaauImage) {
    if (test::runUnderXvfb("command -v xvfb-run > /dev/null") != 0) GTEST_SKIP() << "xvfb-run not installed";
    std::string dir = test::makeTempDir("taau-window");
    const std::string shot = dir + "/view.png", taau = dir + "/taau.png", spatial = dir + "/spatial.png";
    ASSERT_EQ(test::runUnderXvfb(std::string(GLIMMER_EXECUTABLE " view --scene plane25 --env none --size 128x128"
                                             " --render-scale 0.5 --target-fps 0 --set aa=taa --hide-ui --frames 8"
                                             " --screenshot ") + shot + " > /dev/null 2>&1"),
              0);
    const std::vector<std::string> base = {"render", "--scene", "plane25", "--env", "none", "--size", "128x128",
                                           "--render-scale", "0.5", "--frames", "8"};
    std::vector<std::string> args = base;
    args.insert(args.end(), {"--set", "aa=taa", "--out", taau});
    ASSERT_EQ(test::runGlimmer(args).exitCode, 0);
    args = base;
    args.insert(args.end(), {"--out", spatial});
    ASSERT_EQ(test::runGlimmer(args).exitCode, 0);
    ImageF window = readImage(shot), offscreen = readImage(taau), upscaled = readImage(spatial);
    ASSERT_EQ(window.width, 128);
    ASSERT_EQ(offscreen.width, 128);
    auto meanDifference = [](const ImageF& a, const ImageF& b) {
        double sum = 0.0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x)
                for (int c = 0; c < 3; ++c) sum += std::abs(a.at(x, y, c) - b.at(x, y, c));
        return sum / double(a.width * a.height * 3);
    };
    double toTaau = meanDifference(window, offscreen), toSpatial = meanDifference(window, upscaled);
    std::printf("  window vs offscreen TAAU %.5f, vs no AA + Catmull-Rom %.5f (mean abs, display values)\n", toTaau,
                toSpatial);
    EXPECT_LT(toTaau, 0.5 / 255.0);
    EXPECT_GT(toSpatial, 10.0 * std::max(toTaau, 1e-4));
}


// The jitter cycle grows with the upscale ratio (max(16, ceil(8 r^2))) and repeats after that many phases; every
// phase is inside the internal pixel, and over one cycle at r = 2 each quarter of the pixel (each output pixel it
// covers) receives 8 +- 1 samples (Halton (2, 3) is stratified exactly in x, within one point in y here).
TEST(ImageTaau, JitterCycleCoversTheUpscaleRatio) {
    EXPECT_EQ(image::jitterPhases(1.0f), 16);
    EXPECT_EQ(image::jitterPhases(1.25f), 16);
    EXPECT_EQ(image::jitterPhases(2.0f), 32);
    EXPECT_EQ(image::jitterPhases(1.0f / 0.35f), 66);
    EXPECT_EQ(image::jitterPhases(4.0f), 128);
    EXPECT_EQ(image::haltonJitter(0, 32), glm::vec2(0.0f)) << "the first frame after a reset is unjittered";
    int quarters[2][2] = {{0, 0}, {0, 0}};
    for (unsigned frame = 1; frame <= 32; ++frame) {
        glm::vec2 j = image::haltonJitter(frame, 32);
        EXPECT_EQ(j, image::haltonJitter(frame + 32, 32));
        ASSERT_GE(j.x, -0.5f);
        ASSERT_LT(j.x, 0.5f);
        ASSERT_GE(j.y, -0.5f);
        ASSERT_LT(j.y, 0.5f);
        ++quarters[j.x >= 0.0f][j.y >= 0.0f];
    }
    for (auto& row : quarters)
        for (int count : row) EXPECT_NEAR(count, 8, 1);
}

}  // namespace
}  // namespace glimmer
