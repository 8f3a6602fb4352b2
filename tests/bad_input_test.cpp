// Bad input: a one-line error naming the culprit, a non-zero exit, no crash, no output file.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/files.h"
#include "core/image_io.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(BadInput, Process);
GLIMMER_SUITE_NEEDS(RenderCommand, Process);

using glimmer::test::runGlimmer;

// Logs and outputs the tests read back.
constexpr glimmer::InputFileKind kTestText{"test output", uint64_t(64) << 20};

namespace {

struct BadCase {
    std::string name;
    std::vector<std::string> args;
    std::string culprit;   // must appear in the error line
};

int countLines(const std::string& text) {
    int lines = 0;
    for (char c : text) lines += c == '\n';
    return lines + (!text.empty() && text.back() != '\n');
}

void expectCleanFailure(const BadCase& c) {
    glimmer::test::ProcessResult r = runGlimmer(c.args);
    EXPECT_EQ(r.signal, 0) << c.name << ": crashed with signal " << r.signal << "\n" << r.err;
    EXPECT_GT(r.exitCode, 0) << c.name << ": exit code " << r.exitCode;
    EXPECT_EQ(countLines(r.err), 1) << c.name << ": stderr should be one line, was:\n" << r.err;
    EXPECT_NE(r.err.find(c.culprit), std::string::npos) << c.name << ": '" << c.culprit << "' not named in: " << r.err;
    EXPECT_EQ(r.err.rfind("glimmer: ", 0), 0u) << r.err;
}

std::string tempFile(const std::string& dir, const std::string& name, const std::string& contents) {
    std::string path = dir + "/" + name;
    std::ofstream(path) << contents;
    return path;
}

TEST(BadInput, EachGivesAOneLineErrorAndANonZeroExit) {
    std::string dir = glimmer::test::makeTempDir("bad-input");
    std::string out = dir + "/out.png";
    std::string corrupt = tempFile(dir, "corrupt.gltf", "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ {");
    std::string badBuffer = tempFile(dir, "bad-buffer.gltf", R"({"asset":{"version":"2.0"},
        "buffers":[{"byteLength":64,"uri":"missing.bin"}],"bufferViews":[{"buffer":0,"byteLength":36}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})");
    const std::vector<BadCase> cases = {
        {"missing scene file", {"render", "--scene", dir + "/no-such-scene.gltf", "--out", out}, "no-such-scene.gltf"},
        {"corrupt glTF", {"render", "--scene", corrupt, "--out", out}, "corrupt.gltf"},
        {"glTF with a missing buffer", {"render", "--scene", badBuffer, "--out", out}, "bad-buffer.gltf"},
        {"unknown scene name", {"render", "--scene", "atlantis", "--out", out}, "atlantis"},
        {"unknown method", {"render", "--method", "sparklez", "--out", out}, "sparklez"},
        {"unknown --set key", {"render", "--set", "shininess=3", "--out", out}, "shininess"},
        {"unknown IBL mode", {"render", "--ibl", "raytraced", "--out", out}, "raytraced"},
        {"unknown IBL parameter", {"render", "--set", "ibl.samples=3", "--out", out}, "ibl.samples"},
        {"--set out of range", {"render", "--set", "material.alpha=7", "--out", out}, "material.alpha"},
        {"--set not a number", {"render", "--set", "exposure=bright", "--out", out}, "exposure"},
        {"bad --size (zero)", {"render", "--size", "0x256", "--out", out}, "--size"},
        {"bad --size (text)", {"render", "--size", "huge", "--out", out}, "--size"},
        {"--render-scale out of range", {"render", "--render-scale", "2", "--out", out}, "--render-scale"},
        {"--render-scale with --aov", {"render", "--render-scale", "0.5", "--aov", "depth", "--out", out}, "--aov"},
        {"bad --size (too large)", {"render", "--size", "100000x100000", "--out", out}, "--size"},
        // A missing --out folder is created (issue 39, 13); one that cannot be (a file in the way) is an error.
        {"uncreatable --out directory", {"render", "--out", tempFile(dir, "a-file", "x") + "/sub/out.png"}, "--out"},
        {"unwritable --out file", {"render", "--out", "/proc/glimmer.png"}, "--out"},
        {"unsupported --out type", {"render", "--out", dir + "/out.jpg"}, "--out"},
        {"unknown camera", {"render", "--scene", "sphere", "--camera", "drone", "--out", out}, "drone"},
        {"unknown aov", {"render", "--aov", "sparkle", "--out", out}, "sparkle"},
        {"unknown backend", {"render", "--backend", "vulkan", "--out", out}, "vulkan"},
        {"unknown argument", {"render", "--colour", "red", "--out", out}, "--colour"},
        {"missing environment map", {"render", "--env", dir + "/sky.hdr", "--out", out}, "sky.hdr"},
        {"missing --out", {"render", "--scene", "sphere"}, "--out"},
    };
    for (const BadCase& c : cases) expectCleanFailure(c);
    EXPECT_FALSE(std::filesystem::exists(out)) << "a failed render left an output file";
}

TEST(BadInput, ShaderCompileErrorNamesFileAndLine) {
    std::string dir = glimmer::test::makeTempDir("bad-shader");
    std::filesystem::path root = std::filesystem::path(dir) / "shaders";
    std::filesystem::copy(glimmer::defaultShaderDir(), root, std::filesystem::copy_options::recursive);
    // Break line 12 of an included file: the error must point at that file and line, not at the expanded source.
    std::filesystem::path file = root / "common" / "brdf.glsl";
    std::string text = glimmer::readInputFile(file, glimmer::kShaderFileInput);
    std::vector<std::string> lines;
    size_t start = 0;
    for (size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) lines.push_back(text.substr(start, end - start));
    ASSERT_GT(lines.size(), 12u);
    lines[11] = "    float a2 = alpha * alpha +;  // broken on purpose";
    std::ofstream rewritten(file, std::ios::trunc);
    for (const std::string& l : lines) rewritten << l << "\n";
    rewritten.close();
    expectCleanFailure({"shader compile error", {"render", "--shader-dir", root.string(), "--out", dir + "/o.png"},
                        "common/brdf.glsl:12:"});
}

TEST(BadInput, HelpAndListingsSucceed) {
    for (const auto& args : std::vector<std::vector<std::string>>{
             {"render", "--help"}, {"render", "--list-params"}, {"render", "--list-aovs"}, {"--help"}}) {
        glimmer::test::ProcessResult r = runGlimmer(args);
        EXPECT_EQ(r.exitCode, 0) << args.back() << ": " << r.err;
        EXPECT_FALSE(r.out.empty());
    }
    glimmer::test::ProcessResult r = runGlimmer({"render", "--list-params"});
    for (const char* expected : {"exposure", "material.alpha", "material.ndf", "Method smooth"})
        EXPECT_NE(r.out.find(expected), std::string::npos) << expected;
}

TEST(RenderCommand, WritesPngAndExrAndPrintsStats) {
    std::string dir = glimmer::test::makeTempDir("render-ok");
    glimmer::test::ProcessResult png = runGlimmer({"render", "--scene", "sphere", "--method", "smooth", "--size", "64x48", "--out", dir + "/a.png"});
    ASSERT_EQ(png.exitCode, 0) << png.err;
    EXPECT_NE(png.out.find("a.png"), std::string::npos);
    glimmer::test::ProcessResult exr =
        runGlimmer({"render", "--scene", "sphere", "--method", "smooth", "--size", "64x48", "--stats", "--backend", "osmesa",
                    "--out", dir + "/a.exr"});
    ASSERT_EQ(exr.exitCode, 0) << exr.err;
    nlohmann::json stats = nlohmann::json::parse(exr.out);
    EXPECT_EQ(stats["resolution"][0], 64);
    EXPECT_EQ(stats["resolution"][1], 48);
    EXPECT_EQ(stats["backend"], "osmesa");
    EXPECT_EQ(stats["method"], "smooth");
    EXPECT_TRUE(stats["gl_renderer"].is_string());
    // The frame's passes (shadow_sun: the scene's sun, first frame); on-demand work of a new scene (the
    // sky-visibility bake or load, the probes' capture) is listed under names with a dot.
    std::vector<std::string> framePasses;
    for (const auto& pass : stats["passes"]) {
        std::string name = pass.is_object() ? pass.value("name", std::string()) : std::string();
        if (name.find('.') == std::string::npos) framePasses.push_back(name);
    }
    EXPECT_EQ(framePasses,
              (std::vector<std::string>{"shadow_sun", "gbuffer", "gtao", "ao_resolve", "shadow_mask", "lighting",
                                        "tonemap"}))
        << stats["passes"].dump();
    EXPECT_GT(stats["counts"]["triangles"].get<int>(), 0);
    // EXR: linear float radiance, not tone-mapped (the highlight exceeds 1).
    glimmer::ImageF image = glimmer::readImage(dir + "/a.exr");
    ASSERT_EQ(image.width, 64);
    ASSERT_EQ(image.height, 48);
    float peak = 0.0f;
    for (float v : image.pixels) peak = std::max(peak, v);
    EXPECT_GT(peak, 1.0f);
    glimmer::ImageF pngImage = glimmer::readImage(dir + "/a.png");
    EXPECT_EQ(pngImage.width, 64);
}

}  // namespace

namespace {

const std::string kHostile = std::string(GLIMMER_TEST_DIR) + "/data/hostile/";

// stderr lines that are not warnings: a hostile file gives exactly one, the last.
std::vector<std::string> errorLines(const std::string& err) {
    std::vector<std::string> lines;
    size_t start = 0;
    for (size_t end; (end = err.find('\n', start)) != std::string::npos; start = end + 1) {
        std::string line = err.substr(start, end - start);
        if (line.rfind("glimmer: warning:", 0) != 0) lines.push_back(line);
    }
    if (start < err.size()) lines.push_back(err.substr(start));
    return lines;
}

TEST(BadInput, HostileFilesOfIssue14FailCleanlyInBoundedTime) {
    std::string dir = glimmer::test::makeTempDir("hostile-cli");
    std::string out = dir + "/out.png";
    struct Case { std::string file, field; };
    const std::vector<Case> cases = {
        {"crash-bufferview-offset-wrap.gltf", "byteOffset"}, {"oob-read-accessor-offset-wrap.gltf", "byteOffset"},
        {"oob-read-bufferview-offset-wrap.gltf", "byteOffset"}, {"overread-index-count-2.gltf", "no mesh to render"},
        {"mem-accessor-count-1e9.gltf", "count"}, {"hang-node-dag-2pow26.gltf", "nodes"},
        {"blank-huge-positions.gltf", "POSITION"}, {"json/inf_num.json", "halfExtent"},
        {"json/light_color_neg.json", "lights[0].color"}, {"json/basecolor_neg.json", "materials[0].baseColor"},
        {"json/cam_huge.json", "cameras[0].position"}, {"json/cells_u64.json", "meshes[0].cells"},
    };
    for (const Case& c : cases) {
        auto start = std::chrono::steady_clock::now();
        glimmer::test::ProcessResult r = runGlimmer({"render", "--scene", kHostile + c.file, "--size", "32x32", "--out", out});
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_TRUE(r.exitCode == 1 || r.exitCode == 2) << c.file << ": exit " << r.exitCode << " signal " << r.signal << "\n" << r.err;
        std::vector<std::string> errors = errorLines(r.err);
        ASSERT_EQ(errors.size(), 1u) << c.file << ":\n" << r.err;
        EXPECT_NE(errors[0].find(std::filesystem::path(c.file).filename().string()), std::string::npos) << errors[0];
        EXPECT_NE(errors[0].find(c.field), std::string::npos) << c.file << ": '" << c.field << "' not in " << errors[0];
        EXPECT_LT(seconds, 30.0) << c.file;
    }
    for (const char* hdr : {"mem-env-20000x20000-header.hdr", "exit3-env-60000x60000-header.hdr"}) {
        glimmer::test::ProcessResult r = runGlimmer({"render", "--env", kHostile + hdr, "--size", "32x32", "--out", out});
        EXPECT_EQ(r.exitCode, 1) << hdr << "\n" << r.err;
        ASSERT_EQ(errorLines(r.err).size(), 1u) << r.err;
        EXPECT_NE(r.err.find(hdr), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("header size"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(out));
    glimmer::test::ProcessResult ok = runGlimmer({"render", "--scene", kHostile + "ok-baseline.gltf", "--size", "32x32", "--out", out});
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
    EXPECT_TRUE(std::filesystem::exists(out));
}

TEST(BadInput, FailedWritesExitNonZeroAndLeaveNothingHalfWritten) {
    std::string dir = glimmer::test::makeTempDir("failed-writes");
    std::string fifo = dir + "/pipe.png";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    for (const std::string& target : {fifo, std::string("/dev/full")}) {
        glimmer::test::ProcessResult r = runGlimmer({"render", "--scene", "sphere", "--size", "32x32", "--out", target});
        // 1 (not a regular file) for the FIFO, which must not block; 2 for /dev/full (no image extension).
        EXPECT_TRUE(r.exitCode == 1 || r.exitCode == 2) << target << ": " << r.err;
        EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
    }
    // A full disk, simulated by a file size limit: the old image stays, no temporary file remains.
    std::string out = dir + "/image.png";
    std::ofstream(out) << "previous";
    std::string command = "ulimit -f 2; trap '' XFSZ; exec '" + std::string(GLIMMER_EXECUTABLE) +
                          "' render --scene sphere --size 256x256 --out '" + out + "' >'" + dir + "/log' 2>&1";
    int status = std::system(("bash -c \"" + command + "\"").c_str());
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1) << glimmer::readInputFile(dir + "/log", kTestText);
    EXPECT_EQ(glimmer::readInputFile(out, kTestText), "previous");
    size_t files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
    EXPECT_EQ(files, 3u) << "pipe, image and log only";
    // --screenshot into a missing folder fails before anything is rendered (no window needed to see it).
    auto start = std::chrono::steady_clock::now();
    glimmer::test::ProcessResult shot = runGlimmer({"view", "--frames", "1", "--screenshot", dir + "/missing/shot.png"});
    EXPECT_EQ(shot.exitCode, 1) << shot.err;
    EXPECT_NE(shot.err.find("--screenshot"), std::string::npos) << shot.err;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

}  // namespace

namespace {

// fuzz-hang-100226 (issue 14), rebuilt from generated content: a textured material with uvScale [65538, 2] made
// llvmpipe's uncapped anisotropic filter scan millions of texels per pixel (minutes per frame). The G-buffer
// now reads such footprints from a coarse level (shaders/frame/gbuffer.frag): the render finishes in seconds.
TEST(BadInput, HugeUvScaleRendersInBoundedTime) {
    std::string dir = glimmer::test::makeTempDir("huge-uv-scale");
    std::vector<uint8_t> texture(64 * 64 * 4);
    for (size_t i = 0; i < texture.size(); ++i) texture[i] = uint8_t((i * 37) ^ (i >> 7));
    glimmer::writePng(dir + "/noise.png", texture.data(), 64, 64);
    std::ofstream(dir + "/scene.json") << R"({"meshes":[{"name":"g","generator":"plane","halfExtent":2,"cells":4},
        {"name":"s","generator":"sphere","radius":0.3,"segments":16,"rings":8}],
      "materials":[{"name":"m","baseColorTexture":"noise.png","normalTexture":"noise.png","uvScale":[65538,2],
        "uvRotationDegrees":30,"alphaCutoff":0.5}],
      "instances":[{"mesh":"g","material":"m"},{"mesh":"s","material":"m","translation":[0,0.3,0]}],
      "cameras":[{"name":"c","position":[0,2,4],"target":[0,0,0]}]})";
    auto start = std::chrono::steady_clock::now();
    glimmer::test::ProcessResult r = runGlimmer({"render", "--scene", dir + "/scene.json", "--size", "96x96", "--out", dir + "/out.exr"});
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_LT(seconds, 60.0) << "before the fix this took minutes";
    glimmer::ImageF image = glimmer::readImage(dir + "/out.exr");
    for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v));
}

}  // namespace
