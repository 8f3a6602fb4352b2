// glimmer bench (engine/bench/bench.h), its outputs and plot script, render --compare (bench/compare.h) and the
// temporal flicker measure (bench/temporal.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>

#include "bench/bench.h"
#include "bench/compare.h"
#include "bench/temporal.h"
#include "core/error.h"
#include "core/image_io.h"
#include "glints/methods.h"
#include "offscreen/offscreen.h"
#include "support/golden.h"
#include "support/process.h"
#include "support/test_needs.h"
#include "ui/font.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(BenchSuite, GlContext);
GLIMMER_SUITE_NEEDS(BenchCommand, Process);
GLIMMER_SUITE_NEEDS(BenchPlot, Process);
GLIMMER_SUITE_NEEDS(BenchCompare, GlContext);
GLIMMER_SUITE_NEEDS(BenchTemporalRender, GlContext);
GLIMMER_SUITE_NEEDS(BenchSplitView, Window);

using namespace glimmer;
using namespace glimmer::bench;

namespace {

bool positiveFinite(const nlohmann::json& v) { return v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() > 0; }

std::string readAll(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<std::string> methodIds() {
    std::vector<std::string> ids;
    for (const GlintMethod& m : glintMethods()) ids.push_back(m.id);
    return ids;
}

// A tiny run of the Deliot & Belcour suite on the two planes, shared by the schema tests.
const nlohmann::json& tinySuiteJson() {
    static const nlohmann::json json = [] {
        BenchOptions options;
        options.suite = "deliot2023-table1";
        options.scenes = {"plane90", "plane25"};
        options.width = options.height = 64;
        options.frames = 2;
        options.warmup = 1;
        return toJson(runBench(options));
    }();
    return json;
}

// The run's derived figures (checked in the same test: the run is most of a minute on llvmpipe).
void expectDerivedFiguresPositiveAndFinite(const nlohmann::json& derived) {
    for (const std::string& method : methodIds()) {
        SCOPED_TRACE(method);
        ASSERT_TRUE(derived.contains(method));
        const nlohmann::json& d = derived[method];
        EXPECT_TRUE(positiveFinite(d["overhead_vs_smooth"]));
        EXPECT_TRUE(positiveFinite(d["stability_max_over_min"]));
        EXPECT_GE(d["stability_max_over_min"].get<double>(), 1.0);
        EXPECT_TRUE(positiveFinite(d["anisotropy_plane25_over_plane90"]));
        EXPECT_TRUE(positiveFinite(d["speedup_over_zirr2016"]));
        EXPECT_TRUE(positiveFinite(d["ratio_to_deliot2023"]));
        EXPECT_TRUE(positiveFinite(d["cpu"]["overhead_vs_smooth"]));
        EXPECT_TRUE(positiveFinite(d["cpu"]["anisotropy_plane25_over_plane90"]));
    }
    EXPECT_DOUBLE_EQ(derived["smooth"]["overhead_vs_smooth"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(derived["zirr2016"]["speedup_over_zirr2016"].get<double>(), 1.0);
}

}  // namespace

TEST(BenchSuite, TinySuiteJsonHasEveryCaseSamplePassAndDerivedFigure) {
    const nlohmann::json& json = tinySuiteJson();
    EXPECT_EQ(json["schema"], "glimmer-bench/1");
    const nlohmann::json& meta = json["meta"];
    EXPECT_EQ(meta["suite"], "deliot2023-table1");
    EXPECT_EQ(meta["resolution"], nlohmann::json({64, 64}));
    ASSERT_TRUE(meta["gl_renderer"].is_string());
    EXPECT_FALSE(meta["gl_renderer"].get<std::string>().empty());
    ASSERT_TRUE(meta["gpu_timers_meaningful"].is_boolean());
    if (meta["gl_renderer"].get<std::string>().find("llvmpipe") != std::string::npos)
        EXPECT_FALSE(meta["gpu_timers_meaningful"].get<bool>());

    // 2 scenes x every method x 4 densities, each with 2 samples of 3 passes.
    const std::vector<std::string> methods = methodIds();
    const nlohmann::json& results = json["results"];
    ASSERT_EQ(results.size(), 2 * methods.size() * 4);
    std::set<std::string> seenMethods;
    std::set<double> densities;
    for (const nlohmann::json& r : results) {
        seenMethods.insert(r["method"].get<std::string>());
        densities.insert(r["sweep_value"].get<double>());
        EXPECT_EQ(r["sweep_param"], "material.density_scale");
        EXPECT_EQ(r["variant"], "beckmann a=1.0");
        ASSERT_EQ(r["samples"].size(), 2u);
        for (const nlohmann::json& s : r["samples"]) {
            EXPECT_TRUE(positiveFinite(s["wall_ms"])) << s.dump();
            EXPECT_GE(s["cpu_ms"].get<double>(), 0.0);
            std::set<std::string> passes;
            for (const nlohmann::json& p : s["passes"]) passes.insert(p["name"].get<std::string>());
            EXPECT_TRUE(passes.count("lighting")) << s.dump();
        }
        double lo = r["min_ms"], hi = r["max_ms"], mid = r["median_ms"];
        EXPECT_LE(lo, mid);
        EXPECT_LE(mid, hi);
        EXPECT_TRUE(positiveFinite(r["ratio_to_smooth"])) << r.dump();
        if (r["method"] == "smooth") EXPECT_DOUBLE_EQ(r["ratio_to_smooth"].get<double>(), 1.0);
    }
    EXPECT_EQ(seenMethods, std::set<std::string>(methods.begin(), methods.end()));
    EXPECT_EQ(densities, (std::set<double>{0.01, 0.1, 1.0, 10.0}));
    expectDerivedFiguresPositiveAndFinite(json["derived"]);
}

// The derived figures against hand-computed values on a synthetic report.
TEST(BenchDerived, FiguresMatchHandComputedValues) {
    BenchReport report;
    auto add = [&](const std::string& scene, const std::string& method, double density, double ms) {
        BenchResult r;
        r.benchCase = {scene, "v", method, "material.density_scale", density, {}};
        r.medianMs = r.minMs = r.maxMs = ms;
        report.results.push_back(r);
    };
    add("plane90", "smooth", 1, 2.0);
    add("plane90", "smooth", 10, 2.0);
    add("plane25", "smooth", 1, 2.0);
    add("plane25", "smooth", 10, 2.0);
    add("plane90", "zirr2016", 1, 8.0);
    add("plane90", "zirr2016", 10, 8.0);
    add("plane25", "zirr2016", 1, 16.0);
    add("plane25", "zirr2016", 10, 32.0);
    add("plane90", "fast", 1, 4.0);
    add("plane90", "fast", 10, 6.0);
    add("plane25", "fast", 1, 4.0);
    add("plane25", "fast", 10, 4.0);
    add("plane90", "deliot2023", 1, 2.0);
    add("plane90", "deliot2023", 10, 3.0);
    add("plane25", "deliot2023", 1, 4.0);
    add("plane25", "deliot2023", 10, 2.0);
    deriveFigures(report);
    const nlohmann::json& z = report.derived["zirr2016"];
    const nlohmann::json& f = report.derived["fast"];
    // zirr2016 ratios 4, 4, 8, 16: geometric mean 2^(2+2+3+4)/4 = 2^2.75.
    EXPECT_NEAR(z["overhead_vs_smooth"].get<double>(), std::pow(2.0, 2.75), 1e-12);
    EXPECT_NEAR(z["stability_max_over_min"].get<double>(), 2.0, 1e-12);           // plane25: 32 / 16
    EXPECT_NEAR(z["anisotropy_plane25_over_plane90"].get<double>(), std::sqrt(2.0 * 4.0), 1e-12);
    EXPECT_NEAR(f["overhead_vs_smooth"].get<double>(), std::pow(2.0 * 3.0 * 2.0 * 2.0, 0.25), 1e-12);
    EXPECT_NEAR(f["stability_max_over_min"].get<double>(), 1.5, 1e-12);          // plane90: 6 / 4
    EXPECT_NEAR(f["anisotropy_plane25_over_plane90"].get<double>(), std::sqrt(1.0 * 4.0 / 6.0), 1e-12);
    EXPECT_NEAR(f["speedup_over_zirr2016"].get<double>(), std::pow(2.0 * (8.0 / 6.0) * 4.0 * 8.0, 0.25), 1e-12);
    EXPECT_NEAR(f["ratio_to_deliot2023"].get<double>(), std::pow(2.0 * 2.0 * 1.0 * 2.0, 0.25), 1e-12);
    EXPECT_NEAR(report.derived["deliot2023"]["ratio_to_deliot2023"].get<double>(), 1.0, 1e-12);
    EXPECT_NEAR(report.results[9].ratioToSmooth, 3.0, 1e-12);
    std::string markdown = toMarkdown(report);
    EXPECT_NE(markdown.find("| fast | 4.0-6.0 (2.00-3.00x) | 4.0-4.0 (2.00-2.00x) |"), std::string::npos) << markdown;
}

TEST(BenchCases, SuitesExpandAndAlwaysIncludeSmooth) {
    BenchOptions options;
    options.suite = "kemppinen2025-table3";
    options.methods = {"zirr2016"};
    std::vector<BenchCase> cases = expandCases(options);
    ASSERT_EQ(cases.size(), 2u * 4u * 2u);  // 2 planes x 4 roughness/NDF variants x (smooth, zirr2016)
    for (const BenchCase& c : cases) {
        EXPECT_NE(std::find(c.sets.begin(), c.sets.end(), "light.count=3"), c.sets.end());
        EXPECT_TRUE(c.sweepParam.empty());
    }
    EXPECT_EQ(cases.front().method, "smooth");
    options.suite = "nope";
    EXPECT_THROW(expandCases(options), UsageError);
    options.suite = "";
    options.methods = {"nope"};
    EXPECT_THROW(expandCases(options), UsageError);
}

TEST(BenchCommand, WritesJsonCsvAndMarkdown) {
    std::filesystem::path dir = test::testOutputDir() / "bench";
    std::filesystem::create_directories(dir);
    auto run = test::runGlimmer({"bench", "--scenes", "plane25", "--methods", "zirr2016", "--size", "32x32", "--frames",
                                 "3", "--warmup", "0", "--json", (dir / "b.json").string(), "--csv",
                                 (dir / "b.csv").string(), "--markdown", (dir / "b.md").string()});
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.err.find("[2/2]"), std::string::npos) << run.err;  // progress on stderr
    EXPECT_NE(run.out.find("| zirr2016 |"), std::string::npos) << run.out;
    nlohmann::json json = nlohmann::json::parse(readAll(dir / "b.json"));
    ASSERT_EQ(json["results"].size(), 2u);
    std::string csv = readAll(dir / "b.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 3);  // header + every sample
    EXPECT_EQ(readAll(dir / "b.md"), run.out);
}

TEST(BenchCommand, TemporalAndSuiteListingFromTheExecutable) {
    std::filesystem::path dir = test::testOutputDir() / "bench";
    std::filesystem::create_directories(dir);
    auto run = test::runGlimmer({"bench", "--temporal", "--scenes", "plane25", "--methods", "smooth", "--size", "32x24",
                                 "--frames", "3", "--json", (dir / "t.json").string()});
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find("| plane25 | smooth |"), std::string::npos) << run.out;
    nlohmann::json json = nlohmann::json::parse(readAll(dir / "t.json"));
    EXPECT_EQ(json["schema"], "glimmer-bench-temporal/1");
    ASSERT_EQ(json["results"].size(), 1u);
    EXPECT_EQ(json["results"][0]["flicker_per_pair"].size(), 2u);
    EXPECT_TRUE(std::isfinite(json["results"][0]["flicker_mean"].get<double>()));
    auto list = test::runGlimmer({"bench", "--list-suites"});
    ASSERT_EQ(list.exitCode, 0);
    for (const BenchSuite& suite : benchSuites()) EXPECT_NE(list.out.find(suite.name), std::string::npos);
    auto step = test::runGlimmer({"bench", "--temporal", "--step", "2"});
    EXPECT_EQ(step.exitCode, 2);
    EXPECT_NE(step.err.find("--step"), std::string::npos) << step.err;
}

TEST(BenchCommand, BadInputIsOneLineError) {
    auto suite = test::runGlimmer({"bench", "--suite", "nope"});
    EXPECT_EQ(suite.exitCode, 2);
    EXPECT_NE(suite.err.find("--suite: unknown suite 'nope'"), std::string::npos) << suite.err;
    auto methods = test::runGlimmer({"bench", "--methods", "smooth,nope", "--size", "8x8"});
    EXPECT_EQ(methods.exitCode, 2);
    EXPECT_NE(methods.err.find("nope"), std::string::npos) << methods.err;
    auto json = test::runGlimmer({"bench", "--json", "/nonexistent-dir/x.json"});
    EXPECT_EQ(json.exitCode, 1);
    EXPECT_NE(json.err.find("--json"), std::string::npos) << json.err;
    auto crop = test::runGlimmer({"render", "--compare", "zirr2016", "--crop", "1,2,3", "--out", "/tmp/x.png"});
    EXPECT_EQ(crop.exitCode, 2);
    EXPECT_NE(crop.err.find("--crop"), std::string::npos) << crop.err;
}

TEST(BenchPlot, ScriptMakesPng) {
    // The Debian package installs into the system interpreter, which may not be the first python3 on PATH.
    std::string python;
    for (const char* candidate : {"python3", "/usr/bin/python3"})
        if (python.empty() && std::system((std::string(candidate) + " -c 'import matplotlib' >/dev/null 2>&1").c_str()) == 0)
            python = candidate;
    if (python.empty()) GTEST_SKIP() << "matplotlib missing (Debian: python3-matplotlib)";
    std::filesystem::path dir = test::testOutputDir() / "bench";
    std::filesystem::create_directories(dir);
    // A bench of its own with one glint method beside smooth (2 scenes x 2 methods x 4 densities): the script's
    // grouped bars, sweep whiskers and CPU panel need no more, and the whole table's 2 x every method (what
    // BenchSuite checks, in its own process) cost this test about 12 s more.
    static const nlohmann::json plotJson = [] {
        BenchOptions options;
        options.suite = "deliot2023-table1";
        options.scenes = {"plane90", "plane25"};
        options.methods = {"deliot2023"};
        options.width = options.height = 64;
        options.frames = 2;
        options.warmup = 1;
        return toJson(runBench(options));
    }();
    ASSERT_EQ(plotJson["results"].size(), 2u * 2u * 4u);
    std::ofstream(dir / "plot.json") << plotJson.dump();
    std::filesystem::remove(dir / "plot.png");
    std::string script = std::string(GLIMMER_TEST_DIR) + "/../tools/plot_bench.py";
    std::string command = python + " '" + script + "' '" + (dir / "plot.json").string() + "' '" +
                          (dir / "plot.png").string() + "'";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    ASSERT_TRUE(std::filesystem::exists(dir / "plot.png"));
    EXPECT_GT(std::filesystem::file_size(dir / "plot.png"), 1000u);
}

// Grid geometry, labels drawn with the bitmap font, each tile equal to that method's own render apart from the
// crop frame, crops zoomed.
TEST(BenchCompare, GridTilesEqualSingleRendersWithLabelsAndCrops) {
    RenderRequest base;
    base.scene = "plane25";
    base.width = 96;
    base.height = 64;
    std::vector<CropRect> crops = {{10, 20, 16, 8}};
    CompareGrid grid = renderComparison(base, {"zirr2016", "smooth", "zirr2016"}, crops);
    ASSERT_EQ(grid.tiles.size(), 2u);  // smooth first, duplicates dropped
    EXPECT_EQ(grid.tiles[0].method, "smooth");
    EXPECT_EQ(grid.tiles[1].method, "zirr2016");
    EXPECT_EQ(grid.width, 2 * 96 + 3 * kCompareGap);
    int zoom = std::min((96 - 2) / 16, 64 / 8);  // 5
    ASSERT_EQ(grid.tiles[0].insets.size(), 1u);
    EXPECT_EQ(grid.tiles[0].insets[0].width, 16 * zoom);
    EXPECT_EQ(grid.height, grid.tiles[0].renderY + 64 + kCompareGap + 8 * zoom + 2 + kCompareGap);

    auto pixel = [&](int x, int y) { return &grid.rgba[(size_t(y) * grid.width + x) * 4]; };
    for (const CompareTile& tile : grid.tiles) {
        SCOPED_TRACE(tile.method);
        // Label: exactly the font's lit pixels for the method id, in white, inside the label strip.
        int expectedLit = 0;
        for (char c : tile.method)
            for (uint8_t row : ui::glyphRows(c)) expectedLit += __builtin_popcount(row);
        expectedLit *= kCompareLabelScale * kCompareLabelScale;
        int lit = 0;
        for (int y = 0; y < tile.renderY; ++y)
            for (int x = tile.renderX; x < tile.renderX + 96; ++x) lit += pixel(x, y)[0] == 240;
        EXPECT_EQ(lit, expectedLit);
        EXPECT_GT(lit, 0);

        RenderRequest single = base;
        single.settings.method = tile.method;
        RenderResult alone = renderOffscreen(single);
        // Every pixel equals the single render except the crop's 1-pixel frame (x 9..26, y 19..28), which is red.
        int differing = 0, frame = 0, frameRed = 0;
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 96; ++x) {
                bool inside = x >= 10 && x < 26 && y >= 20 && y < 28;
                bool onFrame = x >= 9 && x <= 26 && y >= 19 && y <= 28 && !inside;
                const uint8_t* p = pixel(tile.renderX + x, tile.renderY + y);
                if (onFrame) {
                    ++frame;
                    frameRed += p[0] == kCropColours[0][0] && p[1] == kCropColours[0][1] && p[2] == kCropColours[0][2];
                    continue;
                }
                for (int c = 0; c < 3; ++c) differing += p[c] != alone.display[(size_t(63 - y) * 96 + x) * 4 + c];
            }
        EXPECT_EQ(differing, 0);
        EXPECT_EQ(frame, 2 * 18 + 2 * 8);
        EXPECT_EQ(frameRed, frame);
        const CropRect& inset = tile.insets[0];
        for (int y = 0; y < inset.height; ++y)
            for (int x = 0; x < inset.width; ++x) {
                int sx = 10 + x / zoom, sy = 20 + y / zoom;
                ASSERT_EQ(pixel(inset.x + x, inset.y + y)[1], alone.display[(size_t(63 - sy) * 96 + sx) * 4 + 1]);
            }
    }
    EXPECT_THROW(renderComparison(base, {"smooth"}, {{90, 0, 16, 8}}), UsageError);
    EXPECT_THROW(parseCrop("1,2,0,4"), UsageError);
}

// Reprojection on the CPU: a surface pattern fixed in the world reprojects with little error; a pattern that
// changes between frames does not; an unchanged frame gives exactly 0.
TEST(BenchTemporal, ReprojectedFlickerSeparatesStableFromPopping) {
    Camera start;
    start.position = {0.0f, 2.0f, 3.0f};
    start.target = {0.0f, 0.0f, 0.0f};
    const int w = 96, h = 64;
    auto frameOf = [&](const Camera& camera, uint32_t noiseSeed) {
        GlintFrame f;
        f.camera = camera;
        f.width = w;
        f.height = h;
        std::mt19937 rng(noiseSeed);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                Ray ray = cameraRay(camera, w, h, x + 0.5, y + 0.5);
                double t = -ray.origin.y / ray.direction.y;  // the ground plane y = 0
                bool hit = ray.direction.y < 0;
                glm::dvec3 p = ray.origin + ray.direction * t;
                f.valid.push_back(hit);
                f.depth.push_back(hit ? float(t) : 0.0f);
                // Smooth pattern in world space (stable) or per-frame noise (popping glints).
                f.glint.push_back(noiseSeed ? unit(rng) : float(1.5 + std::sin(1.3 * p.x) * std::cos(0.9 * p.z)));
            }
        return f;
    };
    std::vector<Camera> path = dollyPath(start, 2, 0.01);
    EXPECT_GT(glm::length(path[1].position - path[0].position), 0.03f);
    FlickerMeasure same = reprojectedFlicker(frameOf(start, 0), frameOf(start, 0));
    EXPECT_EQ(same.flicker, 0.0);
    EXPECT_GT(same.matchedFraction, 0.3);
    FlickerMeasure stable = reprojectedFlicker(frameOf(path[0], 0), frameOf(path[1], 0));
    FlickerMeasure popping = reprojectedFlicker(frameOf(path[0], 1), frameOf(path[1], 2));
    EXPECT_GT(stable.matchedFraction, 0.3);
    EXPECT_LT(stable.flicker, 0.05);
    EXPECT_GT(popping.flicker, 0.5);
}

// --motion orbit and light (CPU): the orbit keeps the camera's distance and height and turns it by step radians a
// frame; the popping measure (second difference) is 0 for a pattern that changes linearly in time (a highlight
// sliding smoothly), exactly |spike| / value for one frame that jumps, and ignores invalid pixels.
TEST(BenchTemporal, OrbitPathAndPoppingMeasure) {
    Camera start;
    start.position = {1.0f, 2.0f, 3.0f};
    start.target = {0.0f, 0.5f, 0.0f};
    std::vector<Camera> orbit = orbitPath(start, 4, 0.1);
    ASSERT_EQ(orbit.size(), 4u);
    for (size_t k = 0; k < orbit.size(); ++k) {
        glm::vec3 a = start.position - start.target, b = orbit[k].position - orbit[k].target;
        EXPECT_NEAR(glm::length(b), glm::length(a), 1e-5f);
        EXPECT_NEAR(b.y, a.y, 1e-6f);
        float turn = std::atan2(a.x, a.z) - std::atan2(b.x, b.z);
        EXPECT_NEAR(std::abs(turn), 0.1f * float(k), 1e-5f) << k;
    }
    auto frame = [](std::vector<float> values) {
        GlintFrame f;
        f.width = int(values.size());
        f.height = 1;
        f.glint = values;
        f.valid.assign(values.size(), 1);
        f.depth.assign(values.size(), 1.0f);
        return f;
    };
    EXPECT_EQ(secondDifference(frame({1, 2, 3}), frame({2, 3, 4}), frame({3, 4, 5})), 0.0);
    EXPECT_NEAR(secondDifference(frame({1, 1}), frame({3, 1}), frame({1, 1})), 2.0 / 4.0, 1e-12);
    GlintFrame spike = frame({3, 100}), before = frame({1, 1}), after = frame({1, 1});
    spike.valid[1] = 0;   // an invalid pixel counts nowhere
    EXPECT_NEAR(secondDifference(before, spike, after), 2.0 / 3.0, 1e-12);
}

// Through the renderer: a static camera gives exactly 0 for a deterministic method; a dolly gives a finite value.
TEST(BenchTemporalRender, StaticCameraGivesZeroAndDollyIsFinite) {
    TemporalOptions options;
    options.scenes = {"plane25"};
    options.methods = {"zirr2016"};
    options.width = 64;
    options.height = 48;
    options.frames = 2;
    options.step = 0.0;
    std::vector<TemporalResult> still = runTemporal(options);
    ASSERT_EQ(still.size(), 1u);
    EXPECT_EQ(still[0].meanFlicker, 0.0);
    EXPECT_GT(still[0].matchedFraction, 0.5);
    options.step = 0.02;
    std::vector<TemporalResult> moving = runTemporal(options);
    EXPECT_TRUE(std::isfinite(moving[0].meanFlicker));
    EXPECT_GT(moving[0].meanFlicker, 0.0);
    nlohmann::json json = temporalToJson(options, moving);
    EXPECT_EQ(json["results"][0]["flicker_per_pair"].size(), 1u);
}

// `glimmer view --split`: left of the divider the left method's image, right of it the split method's, a 2-pixel
// white divider between (under xvfb-run; the window's --hide-ui screenshot equals `glimmer render`).
TEST(BenchSplitView, WindowShowsBothMethodsAroundTheDivider) {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run not installed";
    std::filesystem::path dir = test::testOutputDir() / "bench";
    std::filesystem::create_directories(dir);
    const std::string view = (dir / "split_view.png").string(), left = (dir / "split_smooth.png").string(),
                      right = (dir / "split_zirr2016.png").string();
    std::string command = std::string(GLIMMER_EXECUTABLE) +
                          " view --scene plane25 --method smooth --size 128x96 --frames 2 --hide-ui --split zirr2016 --split-at 0.5"
                          " --screenshot " + view + " >/dev/null 2>&1";
    ASSERT_EQ(test::runUnderXvfb(command), 0) << command;
    for (const auto& [method, out] : {std::pair{"smooth", left}, std::pair{"zirr2016", right}}) {
        auto run = test::runGlimmer({"render", "--scene", "plane25", "--size", "128x96", "--method", method, "--out", out});
        ASSERT_EQ(run.exitCode, 0) << run.err;
    }
    ImageF split = readImage(view), a = readImage(left), b = readImage(right);
    ASSERT_EQ(split.width, 128);
    ASSERT_EQ(split.height, 96);
    int leftDiffer = 0, rightDiffer = 0, methodsDiffer = 0, dividerNotWhite = 0;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 128; ++x)
            for (int c = 0; c < 3; ++c) {
                float v = split.at(x, y, c);
                if (x == 63 || x == 64) dividerNotWhite += v < 0.99f;
                else if (x < 63) leftDiffer += std::abs(v - a.at(x, y, c)) > 1.5f / 255.0f;
                else {
                    rightDiffer += std::abs(v - b.at(x, y, c)) > 1.5f / 255.0f;
                    methodsDiffer += std::abs(a.at(x, y, c) - b.at(x, y, c)) > 1.5f / 255.0f;
                }
            }
    EXPECT_EQ(dividerNotWhite, 0);
    EXPECT_EQ(leftDiffer, 0);
    EXPECT_EQ(rightDiffer, 0);
    EXPECT_GT(methodsDiffer, 20);  // the right half really shows another method
    auto bad = test::runGlimmer({"view", "--split", "nope", "--frames", "1"});
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("nope"), std::string::npos) << bad.err;
}
