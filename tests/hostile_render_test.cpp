// Hostile input on the newer surface (issue 40), end to end through the glimmer executable: the reproducers of
// ../shared/repro3 that need a render, a child process or the command line (method output, camera-path renders,
// --video, --size, check-method's time limit, glTF values that change the image), each asserting the exit code
// and a one-line error naming the file and the key, or the correct image. HostileCpu is CPU only.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/files.h"
#include "core/image_io.h"
#include "render/frame/frame_size_limit.h"
#include "render/mesh_chunks.h"
#include "scene/builtin_scenes.h"
#include "ui/input_script.h"
#include "support/process.h"
#include "support/test_needs.h"

namespace fs = std::filesystem;

GLIMMER_SUITE_NEEDS(HostileRender, Process);

namespace {

const fs::path kData = fs::path(GLIMMER_TEST_DIR) / "data" / "hostile";

double secondsOf(const std::function<void()>& run) {
    auto start = std::chrono::steady_clock::now();
    run();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A failing command: exit `code`, and stderr's last line names every `fields` entry.
void expectOneLineError(const glimmer::test::ProcessResult& run, int code, const std::vector<std::string>& fields) {
    EXPECT_EQ(run.signal, 0) << run.err;
    EXPECT_EQ(run.exitCode, code) << run.err;
    std::string err = run.err;
    while (!err.empty() && err.back() == '\n') err.pop_back();
    std::string last = err.substr(err.rfind('\n') == std::string::npos ? 0 : err.rfind('\n') + 1);
    EXPECT_EQ(last.rfind("glimmer: ", 0), 0u) << run.err;
    for (const std::string& f : fields) EXPECT_NE(last.find(f), std::string::npos) << "'" << f << "' not in: " << last;
}

nlohmann::json renderStats(const std::string& method, const std::string& out, glimmer::test::ProcessResult& run,
                           const std::string& scene = "plane90") {
    run = glimmer::test::runGlimmer({"render", "--scene", scene, "--method-file", method, "--env", "none", "--size", "32x32",
                                     "--out", out, "--stats"});
    EXPECT_EQ(run.exitCode, 0) << run.err;
    return nlohmann::json::parse(run.out, nullptr, false);
}

// ---- method output (repro3 method-nan, method-negative, method-loop-forever) ----

TEST(HostileRender, ANanNegativeOrRunawayMethodIsReportedNotSilent) {
    const std::string dir = glimmer::test::makeTempDir("hostile_render_method");
    glimmer::test::ProcessResult run;
    // NaN: the image was black with non_finite_values 0.
    nlohmann::json nan = renderStats((kData / "method-nan.glsl").string(), dir + "/nan.exr", run);
    EXPECT_GT(nan["method_output"]["non_finite_d"].get<int>(), 0);
    EXPECT_GT(nan["counts"]["non_finite_values"].get<int>(), 0) << "non_finite_values must count what the method produced";
    EXPECT_NE(run.err.find("warning: method 'mine': glintD returned NaN or Inf"), std::string::npos) << run.err;
    // Negative: the EXR held negative radiance and the PNG was white.
    nlohmann::json negative = renderStats((kData / "method-negative.glsl").string(), dir + "/negative.exr", run);
    EXPECT_GT(negative["method_output"]["negative_d"].get<int>(), 0);
    EXPECT_NE(run.err.find("warning: method 'mine': glintD returned a negative value"), std::string::npos) << run.err;
    glimmer::ImageF image = glimmer::readImage(dir + "/negative.exr");
    float lowest = 0.0f;
    for (float v : image.pixels) lowest = std::min(lowest, v);
    EXPECT_GE(lowest, 0.0f) << "negative radiance reached the image";
    // A loop to llvmpipe's iteration cap: radiance ~1e6, implausible.
    nlohmann::json runaway = renderStats((kData / "method-loop-forever.glsl").string(), dir + "/loop.exr", run);
    EXPECT_TRUE(runaway["method_output"]["implausible"].get<bool>()) << runaway["method_output"].dump();
    EXPECT_NE(run.err.find("the radiance is implausible"), std::string::npos) << run.err;
    // A faithful method says nothing: the example method file (deliot2023 with bilinear blending).
    nlohmann::json good = renderStats((fs::path(GLIMMER_SOURCE_DIR) / "content" / "methods" / "deliot2023_smoothstep.glsl").string(),
                                      dir + "/good.exr", run, "plane25");
    EXPECT_FALSE(good["method_output"]["implausible"].get<bool>()) << good["method_output"].dump();
    EXPECT_EQ(good["method_output"]["non_finite_d"].get<int>() + good["method_output"]["negative_d"].get<int>() +
                  good["method_output"]["negative_radiance"].get<int>() + good["counts"]["non_finite_values"].get<int>(), 0);
    EXPECT_EQ(run.err.find("method '"), std::string::npos) << run.err;
}

// check-method on the runaway method ran past 120 s: each rule now has a time limit.
TEST(HostileRender, CheckMethodHasATimeLimitPerRule) {
    glimmer::test::ProcessResult run;
    double seconds = secondsOf([&] {
        run = glimmer::test::runGlimmer({"check-method", (kData / "method-loop-forever.glsl").string(), "--rules", "finite",
                                         "--rule-seconds", "3"});
    });
    EXPECT_EQ(run.exitCode, 1) << run.out << run.err;
    const std::string row = run.out.substr(std::min(run.out.find("\nfinite "), run.out.size()));
    EXPECT_NE(row.find("FAIL    did not finish within 3 s"), std::string::npos) << run.out;
    EXPECT_NE(run.err.find("rule failed: finite"), std::string::npos) << run.err;
    EXPECT_LT(seconds, 30.0);
}

// ---- glTF values that change the image ----

TEST(HostileRender, GlintDensitiesRenderAsWritten) {
    const std::string dir = glimmer::test::makeTempDir("hostile_render_density");
    auto render = [&](const std::string& model) {
        glimmer::test::ProcessResult run = glimmer::test::runGlimmer(
            {"render", "--scene", (kData / model).string(), "--env", "none", "--size", "64x64", "--out", dir + "/" + model + ".exr"});
        EXPECT_EQ(run.exitCode, 0) << run.err;
        return glimmer::readImage(dir + "/" + model + ".exr").pixels;
    };
    // 10000000000 as an integer renders as 1e10 does (it wrapped to 1410065408), 4294967296 unlike density 0 (it
    // wrapped to 0), and density 0 has no glints: its image equals the floor's with the method's D at zero.
    EXPECT_EQ(render("glint-density-int-1e10.gltf"), render("glint-density-float-1e10-control.gltf"));
    std::vector<float> zero = render("glint-density-0-control.gltf"), wide = render("glint-density-int-2p32.gltf");
    EXPECT_NE(zero, wide);
    glimmer::test::ProcessResult run = glimmer::test::runGlimmer(
        {"render", "--scene", (kData / "glint-density-0-control.gltf").string(), "--env", "none", "--size", "64x64",
         "--aov", "glint", "--out", dir + "/zero-glint.exr"});
    ASSERT_EQ(run.exitCode, 0) << run.err;
    float largest = 0.0f;
    for (float v : glimmer::readImage(dir + "/zero-glint.exr").pixels) largest = std::max(largest, v);
    EXPECT_LE(largest, 1.0f) << "the glint AOV (D of the first light) is not zero on a density-0 floor";
}

TEST(HostileRender, GltfValueErrorsAreOneLineNamingFileAndKey) {
    struct Case { const char* model; std::vector<std::string> fields; };
    for (const Case& c : {Case{"emissive-strength-int-2p32plus1.gltf", {"emissiveStrength", "4294967297"}},
                          Case{"glint-extension-not-object.gltf", {"GLIMMER_materials_glint", "expected an object"}},
                          Case{"clearcoat-extension-not-object.gltf", {"KHR_materials_clearcoat", "expected an object"}},
                          Case{"glint-color-with-null-4-items.gltf", {"GLIMMER_materials_glint.color"}},
                          Case{"light-intensity-string.gltf", {"lights[0].intensity"}},
                          Case{"alpha-mask-cutoff-2.gltf", {"materials[1].alphaCutoff"}},
                          Case{"camera-znear-1e5.gltf", {"cameras[0].perspective.znear"}}}) {
        glimmer::test::ProcessResult run = glimmer::test::runGlimmer(
            {"render", "--scene", (kData / c.model).string(), "--env", "none", "--size", "16x16", "--out", "/tmp/unused.exr"});
        std::vector<std::string> fields = c.fields;
        fields.push_back(c.model);
        expectOneLineError(run, 1, fields);
    }
    // A light on a zero-scale node is skipped with a warning, like a mesh; the model renders.
    glimmer::test::ProcessResult light = glimmer::test::runGlimmer(
        {"render", "--scene", (kData / "light-point-on-zero-scale-node.gltf").string(), "--env", "none", "--size", "16x16",
         "--out", glimmer::test::makeTempDir("hostile_render_light") + "/light.exr"});
    EXPECT_EQ(light.exitCode, 0) << light.err;
    EXPECT_NE(light.err.find("node 5 has a singular or non-finite transform (zero scale); its light is skipped"), std::string::npos)
        << light.err;
}

// repro3 wrong-texture-emissive-after-model: the green emissive quad rendered red.
TEST(HostileRender, AMergedModelsEmissiveTextureIsItsOwn) {
    const std::string out = glimmer::test::makeTempDir("hostile_render_emissive") + "/quad.exr";
    glimmer::test::ProcessResult run = glimmer::test::runGlimmer(
        {"render", "--scene", (kData / "wrong-texture-emissive-after-model" / "scene.json").string(), "--env", "none",
         "--size", "32x32", "--out", out});
    ASSERT_EQ(run.exitCode, 0) << run.err;
    glimmer::ImageF image = glimmer::readImage(out);
    double red = 0.0, green = 0.0;
    for (size_t i = 0; i + 3 < image.pixels.size(); i += size_t(image.channels)) red += image.pixels[i], green += image.pixels[i + 1];
    EXPECT_GT(green, 100.0) << "the quad is not green";
    EXPECT_LT(red, 0.01 * green) << "the quad took the first model's red texture";
}

// ---- camera paths, --video, --size ----

TEST(HostileRender, BadCameraPathsFailBeforeAnyFrame) {
    const std::string dir = glimmer::test::makeTempDir("hostile_render_path");
    struct Case { const char* file; std::vector<std::string> fields; };
    for (const Case& c : {Case{"path-t-1e300.json", {"samples[1].t"}},
                          Case{"path-t-1e5.json", {"3000001 frames", "limit of 1000000"}},
                          Case{"path-look-straight-down.json", {"samples[0].forward"}},
                          Case{"path-near-0.json", {"samples[0].near"}},
                          Case{"path-fov-179.json", {"samples[0].fov"}}}) {
        glimmer::test::ProcessResult run;
        double seconds = secondsOf([&] {
            run = glimmer::test::runGlimmer({"render", "--path", (kData / c.file).string(), "--scene", "plane25", "--env", "none",
                                             "--size", "16x16", "--out", dir + "/%04d.png"});
        });
        std::vector<std::string> fields = c.fields;
        fields.push_back(c.file);
        expectOneLineError(run, 1, fields);
        EXPECT_LT(seconds, 20.0) << c.file;
    }
    EXPECT_TRUE(fs::is_empty(dir)) << "frames were written";
    glimmer::test::ProcessResult devZero = glimmer::test::runGlimmer({"render", "--path", "/dev/zero", "--out", dir + "/%04d.png"});
    expectOneLineError(devZero, 1, {"/dev/zero", "not a regular file"});
}

// --video left a predictable /tmp/glimmer-frames-PID folder behind when ffmpeg failed. A stand-in ffmpeg that fails,
// and TMPDIR pointing at an empty folder: nothing may remain there.
TEST(HostileRender, AFailedVideoLeavesNoFramesBehind) {
    const std::string dir = glimmer::test::makeTempDir("hostile_render_video");
    fs::create_directories(dir + "/bin");
    fs::create_directories(dir + "/tmp");
    {
        std::ofstream ffmpeg(dir + "/bin/ffmpeg");
        ffmpeg << "#!/bin/sh\necho 'stand-in ffmpeg fails' >&2\nexit 1\n";
    }
    fs::permissions(dir + "/bin/ffmpeg", fs::perms::owner_all);
    std::ofstream(dir + "/path.json") << R"({"samples": [{"t": 0, "position": [0, 1, 3], "forward": [0, -0.2, -1]},
                                                       {"t": 0.04, "position": [0, 1, 2.9], "forward": [0, -0.2, -1]}]})";
    glimmer::test::ProcessResult run = glimmer::test::runGlimmer(
        {"render", "--path", dir + "/path.json", "--scene", "plane25", "--env", "none", "--size", "16x16", "--video", dir + "/out.mp4"},
        {"PATH=" + dir + "/bin:/usr/bin:/bin", "TMPDIR=" + dir + "/tmp"});
    expectOneLineError(run, 1, {"--video", "ffmpeg failed"});
    EXPECT_TRUE(fs::is_empty(dir + "/tmp")) << "a frames folder was left in TMPDIR";
    EXPECT_FALSE(fs::exists(dir + "/out.mp4"));
}

TEST(HostileRender, AnImpossibleSizeIsRefusedBeforeAllocating) {
    glimmer::test::ProcessResult run;
    double seconds = secondsOf([&] {
        run = glimmer::test::runGlimmer({"render", "--scene", "plane90", "--size", "16384x16384", "--env", "none", "--out",
                                         "/tmp/unused.png"});
    });
    // On a machine with more than ~100 GB free the frame fits and would render: nothing to test there.
    glimmer::FrameSizeLimit limit;
    limit.maxSide = 16384;
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    uint64_t kib = 0;
    std::string unit;
    while (meminfo >> key >> kib >> unit)
        if (key == "MemAvailable:") limit.availableBytes = kib * 1024;
    if (uint64_t(16384) * 16384 * glimmer::kFrameBytesPerPixel <= limit.availableBytes) GTEST_SKIP() << "enough memory for 16384^2";
    expectOneLineError(run, 2, {"--size", "16384x16384", "memory available"});
    EXPECT_LT(seconds, 20.0);
}

TEST(HostileCpu, FrameSizeLimitNamesTheFlagAndTheLimit) {
    glimmer::FrameSizeLimit limit{4096, uint64_t(1) << 30};
    EXPECT_NO_THROW(glimmer::checkFrameSize(1024, 1024, limit, "--size"));
    try {
        glimmer::checkFrameSize(8192, 16, limit, "--size");
        ADD_FAILURE() << "8192 wide accepted";
    } catch (const glimmer::UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("--size: 8192x16 exceeds this GL context's largest frame side of 4096"), std::string::npos) << e.what();
    }
    try {
        glimmer::checkFrameSize(4096, 4096, limit, "--size");   // 16 M pixels x 400 B > 1 GiB
        ADD_FAILURE() << "4096^2 accepted with 1 GiB";
    } catch (const glimmer::UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("memory available"), std::string::npos) << e.what();
    }
}

// repro3's view --input-script on /dev/zero read until memory ran out, and a FIFO hung.
TEST(HostileCpu, InputScriptsAreReadByTheOneReader) {
    const std::string dir = glimmer::test::makeTempDir("hostile_input_script");
    ASSERT_EQ(mkfifo((dir + "/script.txt").c_str(), 0600), 0);
    for (const std::string& path : {std::string("/dev/zero"), dir + "/script.txt", dir}) {
        double seconds = secondsOf([&] {
            try {
                glimmer::ui::readInputScript(path);
                ADD_FAILURE() << path << " was read";
            } catch (const glimmer::Error& e) {
                EXPECT_NE(std::string(e.what()).find(path + ": input script "), std::string::npos) << e.what();
            }
        });
        EXPECT_LT(seconds, 2.0) << path;
    }
}

// repro3 slow-chunks-plane-cells-2048: chunking handed meshoptimizer the whole mesh's vertex count for every chunk
// (quadratic: cells 2048 ran past 120 s). 4x the triangles must cost about 4x the time (fastest of three; a
// quadratic build gives 16x), and the chunks still cover every triangle once.
TEST(HostileCpu, ChunkingIsLinearInTheMesh) {
    auto chunkSeconds = [](int cells, size_t& triangles) {
        glimmer::MeshData plane = glimmer::makeGroundPlane(10.0f, cells, 0.0f);
        triangles = plane.indices.size() / 3;
        double best = 1e30;
        for (int run = 0; run < 3; ++run)
            best = std::min(best, secondsOf([&] {
                glimmer::ChunkedIndices chunked = glimmer::buildMeshChunks(plane.indices, plane.positions);
                size_t covered = 0;
                for (const glimmer::MeshChunk& c : chunked.chunks) covered += c.indexCount;
                EXPECT_EQ(covered, plane.indices.size());
            }));
        return best;
    };
    size_t small = 0, large = 0;
    double tSmall = chunkSeconds(256, small), tLarge = chunkSeconds(512, large);
    EXPECT_EQ(large, 4 * small);
    EXPECT_LT(tLarge / tSmall, 7.0) << "256 cells: " << tSmall << " s, 512 cells: " << tLarge << " s";
}

}  // namespace
