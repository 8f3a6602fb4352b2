// `glimmer render --path`: a camera path rendered at a fixed time step gives the same frames on every run;
// `--video` needs the ffmpeg program and says so in one line when it is missing; the small command-line items
// (--version, main --help) and the shader folder found beside an installed executable.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "support/golden.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(RenderPath, Process);
GLIMMER_SUITE_NEEDS(CommandLine, Process);

namespace glimmer {
namespace {
namespace fs = std::filesystem;

std::string slurp(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

int shell(const std::string& command) {
    int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A 1 s path over plane25: sliding sideways and turning a little.
fs::path writePath(const fs::path& dir) {
    fs::path file = dir / "slide.path.json";
    std::ofstream(file) << R"({"glimmer_camera_path": 1, "scene": "plane25", "samples": [
        {"t": 0.0, "position": [0, 1, 10], "forward": [0, -0.42, -0.9], "fov": 45},
        {"t": 1.0, "position": [1, 1, 9], "forward": [0.2, -0.42, -0.9], "fov": 45}]})";
    return file;
}

std::vector<std::string> pathArgs(const fs::path& path, const fs::path& outDir) {
    return {"render", "--scene", "plane25", "--method", "zirr2016", "--env", "none", "--size", "48x32", "--path",
            path.string(), "--fps", "2", "--out", (outDir / "%03d.png").string()};
}

TEST(RenderPath, WritesTheSameFrameSequenceOnEveryRun) {
    fs::path dir = test::makeTempDir("render-path");
    fs::path path = writePath(dir);
    fs::create_directories(dir / "a");
    fs::create_directories(dir / "b");
    for (const char* run : {"a", "b"}) {
        test::ProcessResult r = test::runGlimmer(pathArgs(path, dir / run));
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    // 1 s at 2 fps: frames at 0, 0.5 and 1 s.
    for (int i = 0; i < 3; ++i) {
        char name[16];
        std::snprintf(name, sizeof name, "%03d.png", i);
        std::string a = slurp(dir / "a" / name), b = slurp(dir / "b" / name);
        ASSERT_FALSE(a.empty()) << name;
        EXPECT_EQ(a, b) << name << " differs between two runs";
    }
    EXPECT_FALSE(fs::exists(dir / "a" / "003.png"));
    EXPECT_NE(slurp(dir / "a" / "000.png"), slurp(dir / "a" / "002.png"));  // the camera moved
}

TEST(RenderPath, BadPathsAndPatternsFailInOneLine) {
    fs::path dir = test::makeTempDir("render-path-bad");
    fs::path path = writePath(dir);
    std::ofstream(dir / "broken.json") << "{\"samples\": 3}";
    struct Case {
        std::vector<std::string> args;
        std::string expect;
    };
    for (const Case& c : std::vector<Case>{
             {{"render", "--path", (dir / "missing.json").string(), "--out", (dir / "%d.png").string()}, "missing.json"},
             {{"render", "--path", (dir / "broken.json").string(), "--out", (dir / "%d.png").string()}, "broken.json"},
             {{"render", "--path", path.string(), "--out", (dir / "frame.png").string()}, "--out"},
             {{"render", "--path", path.string(), "--fps", "0", "--out", (dir / "%d.png").string()}, "--fps"}}) {
        test::ProcessResult r = test::runGlimmer(c.args);
        EXPECT_NE(r.exitCode, 0) << c.expect;
        EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
}

TEST(RenderPath, VideoNeedsFfmpegAndSaysSoWhenItIsMissing) {
    fs::path dir = test::makeTempDir("render-path-video");
    fs::path path = writePath(dir);
    fs::path err = dir / "err.txt";
    // No ffmpeg on PATH: one line naming it, before any frame is rendered.
    int code = shell("env PATH=/nonexistent " GLIMMER_EXECUTABLE " render --scene plane25 --size 48x32 --path " +
                     path.string() + " --video " + (dir / "v.mp4").string() + " > /dev/null 2> " + err.string());
    EXPECT_EQ(code, 1);
    std::string text = slurp(err);
    EXPECT_NE(text.find("ffmpeg"), std::string::npos) << text;
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
    EXPECT_FALSE(fs::exists(dir / "v.mp4"));
    if (shell("command -v ffmpeg > /dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg not installed";
    std::vector<std::string> args = pathArgs(path, dir);
    args.insert(args.end(), {"--video", (dir / "v.mp4").string()});
    test::ProcessResult r = test::runGlimmer(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_GT(fs::file_size(dir / "v.mp4"), 500u);
}

// Issue 39, 7: without --scene a path renders in the scene its file names (the atrium's path rendered plane90);
// a file that names none is a one-line error asking for --scene. With --out, a missing ffmpeg still leaves the
// frames (and fails at the end, saying where they are).
TEST(RenderPath, TheSceneComesFromThePathFileAndFramesSurviveAMissingFfmpeg) {
    fs::path dir = test::makeTempDir("render-path-scene");
    fs::path path = writePath(dir);   // names plane25
    std::vector<std::string> named = pathArgs(path, dir / "named");
    std::vector<std::string> fromFile = named;
    fromFile.erase(fromFile.begin() + 1, fromFile.begin() + 3);   // no --scene plane25
    for (std::string& a : fromFile)
        if (a.find("named") != std::string::npos) a.replace(a.find("named"), 5, "fromfile");
    ASSERT_EQ(test::runGlimmer(named).exitCode, 0);
    test::ProcessResult r = test::runGlimmer(fromFile);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::is_directory(dir / "fromfile")) << "--out's folder was not created";
    EXPECT_EQ(slurp(dir / "named" / "001.png"), slurp(dir / "fromfile" / "001.png"));
    std::vector<std::string> plane90 = named;   // render's default scene: another image (the test can fail)
    plane90[2] = "plane90";
    for (std::string& a : plane90)
        if (a.find("named") != std::string::npos) a.replace(a.find("named"), 5, "plane90");
    ASSERT_EQ(test::runGlimmer(plane90).exitCode, 0);
    EXPECT_NE(slurp(dir / "plane90" / "001.png"), slurp(dir / "fromfile" / "001.png"));
    EXPECT_NE(r.err.find("3 frames at 2 fps cover 1.00 s of the path's 1.00 s"), std::string::npos) << r.err;

    std::string text = slurp(path);
    text.replace(text.find("\"scene\": \"plane25\", "), std::string("\"scene\": \"plane25\", ").size(), "");
    fs::path sceneless = dir / "sceneless.path.json";
    std::ofstream(sceneless) << text;
    test::ProcessResult bad = test::runGlimmer({"render", "--path", sceneless.string(), "--out", (dir / "%d.png").string()});
    EXPECT_EQ(bad.exitCode, 2) << bad.err;
    EXPECT_NE(bad.err.find("sceneless.path.json names no scene"), std::string::npos) << bad.err;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;

    fs::path err = dir / "ffmpeg.txt";
    int code = shell("env PATH=/nonexistent " GLIMMER_EXECUTABLE " render --size 48x32 --env none --path " +
                     path.string() + " --fps 2 --out " + (dir / "kept" / "%03d.png").string() + " --video " +
                     (dir / "v.mp4").string() + " > /dev/null 2> " + err.string());
    EXPECT_EQ(code, 1);
    for (const char* frame : {"000.png", "001.png", "002.png"}) EXPECT_TRUE(fs::exists(dir / "kept" / frame)) << frame;
    EXPECT_NE(slurp(err).find("ffmpeg"), std::string::npos) << slurp(err);
    EXPECT_FALSE(fs::exists(dir / "v.mp4"));
}

TEST(CommandLine, VersionAndMainHelp) {
    test::ProcessResult version = test::runGlimmer({"--version"});
    EXPECT_EQ(version.exitCode, 0);
    EXPECT_EQ(version.out.rfind("glimmer ", 0), 0u) << version.out;
    // main --help is main's own help (it must not open a window or render).
    test::ProcessResult help = test::runGlimmer({"main", "--help"});
    EXPECT_EQ(help.exitCode, 0) << help.err;
    EXPECT_EQ(help.out.rfind("usage: glimmer main", 0), 0u) << help.out;
    EXPECT_FALSE(fs::exists("glimmer-default.png"));
    test::ProcessResult view = test::runGlimmer({"view", "--help"});
    EXPECT_NE(view.out.find("--input-script"), std::string::npos);
    EXPECT_NE(view.out.find("--path"), std::string::npos);
}

// An installed layout (<prefix>/bin/glimmer, <prefix>/share/glimmer/shaders) uses its own shaders: a copy
// whose tonemap shader is broken fails on that file (the source tree's is fine), and GLIMMER_SHADER_DIR overrides it.
TEST(CommandLine, ShadersAreFoundBesideAnInstalledExecutable) {
    fs::path prefix = test::makeTempDir("install-prefix");
    fs::create_directories(prefix / "bin");
    fs::create_directories(prefix / "share" / "glimmer");
    fs::copy_file(GLIMMER_EXECUTABLE, prefix / "bin" / "glimmer");
    fs::permissions(prefix / "bin" / "glimmer", fs::perms::owner_all, fs::perm_options::add);
    fs::path shaders = prefix / "share" / "glimmer" / "shaders";
    fs::copy(fs::path(GLIMMER_TEST_DIR) / ".." / "shaders", shaders, fs::copy_options::recursive);
    std::ofstream(shaders / "image/tonemap.frag", std::ios::app) << "\nnot glsl;\n";
    fs::path err = prefix / "err.txt";
    std::string render = (prefix / "bin" / "glimmer").string() + " render --scene sphere --method smooth --size 16x16 --env none --out " +
                         (prefix / "o.png").string() + " > /dev/null 2> " + err.string();
    EXPECT_EQ(shell("env -u GLIMMER_SHADER_DIR " + render), 1);
    std::string text = slurp(err);
    // Only the installed copy is broken: failing on it shows that copy was the one loaded.
    EXPECT_NE(text.find("tonemap.frag:"), std::string::npos) << text;
    EXPECT_EQ(shell("env GLIMMER_SHADER_DIR=" + (fs::path(GLIMMER_TEST_DIR) / ".." / "shaders").string() + " " + render), 0)
        << slurp(err);
}

}  // namespace
}  // namespace glimmer
