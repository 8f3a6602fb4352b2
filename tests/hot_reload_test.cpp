// Shader hot reload in process (EGL): a Renderer reads a temporary copy of shaders/, the test edits files there
// and checks that the watcher reports them, that the rebuilt program shows in the pixels, that a broken edit
// keeps the last good program (pixels unchanged) and reports file:line, and that fixing it recovers.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "core/file_watcher.h"
#include "core/files.h"
#include "platform/context.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"

namespace glimmer {
namespace {
namespace fs = std::filesystem;
using namespace std::chrono_literals;

class TempShaderCopy {
public:
    explicit TempShaderCopy(const std::string& tag) {
        dir_ = fs::temp_directory_path() / ("glimmer-" + tag + "-" + std::to_string(getpid()));
        fs::remove_all(dir_);
        fs::copy(defaultShaderDir(), dir_, fs::copy_options::recursive);
        dir_ = fs::canonical(dir_);
    }
    ~TempShaderCopy() {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    const fs::path& dir() const { return dir_; }

private:
    fs::path dir_;
};

// Editors either rewrite the file in place (IN_CLOSE_WRITE) or write a temporary and rename it (IN_MOVED_TO).
void writeFile(const fs::path& path, const std::string& text, bool byRename) {
    fs::path target = byRename ? fs::path(path.string() + ".swp") : path;
    {
        std::ofstream out(target, std::ios::binary | std::ios::trunc);
        out << text;
    }
    if (byRename) fs::rename(target, path);
}

// Polls until `file` is reported; returns the milliseconds it took (or -1 after 3 s).
double waitForChange(FileWatcher& watcher, const fs::path& file, std::vector<fs::path>& changed) {
    auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < 3s) {
        changed = watcher.poll();
        if (std::find(changed.begin(), changed.end(), fs::canonical(file)) != changed.end())
            return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        std::this_thread::sleep_for(5ms);
    }
    return -1.0;
}

// CPU reference of shaders/image/tonemap.frag for the final view: exposure 1, ACES fit (Narkowicz), sRGB, 8 bits.
uint8_t displayValue(float linear) {
    float x = linear;
    float aces = std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
    float srgb = aces <= 0.0031308f ? 12.92f * aces : 1.055f * std::pow(aces, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(srgb * 255.0f));
}

struct Fixture {
    std::unique_ptr<GLContext> context;
    Scene scene;
    std::unique_ptr<GpuScene> gpuScene;
    std::unique_ptr<Renderer> renderer;
    Camera camera;

    explicit Fixture(const fs::path& shaderRoot) {
        context = createHeadlessContext(Backend::Egl);
        scene = loadScene("sphere");
        gpuScene = std::make_unique<GpuScene>(scene);
        renderer = std::make_unique<Renderer>(shaderRoot, RenderSettings{});
        camera = scene.camera("");
    }
    ~Fixture() {
        renderer.reset();
        gpuScene.reset();
    }
    std::vector<uint8_t> render() {
        renderer->renderView(scene, *gpuScene, camera, 64, 48);
        return renderer->readDisplay();
    }
};

bool contains(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
}

TEST(HotReload, EditTakesEffectBrokenEditKeepsLastGoodProgramAndFixRecovers) {
    TempShaderCopy copy("hot-reload");
    Fixture f(copy.dir());
    std::vector<uint8_t> baseline = f.render();
    FileWatcher watcher(copy.dir());
    EXPECT_EQ(watcher.mode(), FileWatcher::Mode::Inotify);
    EXPECT_TRUE(watcher.poll().empty());

    // 1. Lighting outputs a constant: wrap the original main and overwrite its result.
    fs::path lighting = copy.dir() / "frame/lighting.frag";
    const std::string original = readTextFile(lighting);
    std::smatch output;
    ASSERT_TRUE(std::regex_search(original, output, std::regex(R"(layout\(location = 0\) out vec4 (\w+);)")));
    std::string constant = std::regex_replace(original, std::regex(R"(void\s+main\s*\(\s*\))"), "void originalMain()");
    constant += "\nvoid main() {\n    originalMain();\n    " + output[1].str() + " = vec4(0.25, 0.5, 1.0, 1.0);\n}\n";
    writeFile(lighting, constant, true);
    std::vector<fs::path> changed;
    double latency = waitForChange(watcher, lighting, changed);
    ASSERT_GE(latency, 0.0) << "the watcher never reported lighting.frag";
    EXPECT_LT(latency, 500.0);
    std::printf("[ measure  ] save -> watcher report: %.1f ms\n", latency);
    std::vector<std::string> rebuilt = f.renderer->reloadChangedPrograms(changed);
    EXPECT_TRUE(contains(rebuilt, "lighting/smooth"));
    EXPECT_FALSE(contains(rebuilt, "gbuffer"));
    EXPECT_FALSE(contains(rebuilt, "tonemap"));
    EXPECT_TRUE(f.renderer->shaderErrors().empty());
    std::vector<uint8_t> constantImage = f.render();
    const uint8_t expected[3] = {displayValue(0.25f), displayValue(0.5f), displayValue(1.0f)};
    size_t wrong = 0;
    for (size_t i = 0; i < constantImage.size(); i += 4)
        for (int c = 0; c < 3; ++c) wrong += std::abs(int(constantImage[i + size_t(c)]) - int(expected[c])) > 1;
    EXPECT_EQ(wrong, 0u) << "every pixel must show the constant radiance tone-mapped";
    EXPECT_NE(constantImage, baseline);

    // 2. A broken edit: the old (constant) program keeps running and the error names file:line.
    std::string broken = constant + "this is not glsl;\n";
    int brokenLine = int(std::count(constant.begin(), constant.end(), '\n')) + 1;
    writeFile(lighting, broken, false);
    ASSERT_GE(waitForChange(watcher, lighting, changed), 0.0);
    rebuilt = f.renderer->reloadChangedPrograms(changed);
    EXPECT_TRUE(rebuilt.empty());
    ASSERT_EQ(f.renderer->shaderErrors().count("lighting/smooth"), 1u);
    const std::string& error = f.renderer->shaderErrors().at("lighting/smooth");
    EXPECT_NE(error.find("lighting.frag:" + std::to_string(brokenLine) + ":"), std::string::npos) << error;
    EXPECT_EQ(f.render(), constantImage);

    // 3. Fixed: back to the original shader, the original pixels and no error.
    writeFile(lighting, original, true);
    ASSERT_GE(waitForChange(watcher, lighting, changed), 0.0);
    rebuilt = f.renderer->reloadChangedPrograms(changed);
    EXPECT_TRUE(contains(rebuilt, "lighting/smooth"));
    EXPECT_TRUE(f.renderer->shaderErrors().empty());
    EXPECT_EQ(f.render(), baseline);
}

TEST(HotReload, IncludedFileRebuildsOnlyTheProgramsThatUseIt) {
    TempShaderCopy copy("hot-reload-include");
    Fixture f(copy.dir());
    fs::path brdf = fs::canonical(copy.dir() / "common" / "brdf.glsl");
    auto deps = f.renderer->shaderDependencies();
    ASSERT_NE(std::find(deps.begin(), deps.end(), brdf), deps.end()) << "shaderDependencies() must list includes";
    FileWatcher watcher(copy.dir());
    writeFile(brdf, readTextFile(brdf) + "\n// touched by the test\n", false);
    std::vector<fs::path> changed;
    ASSERT_GE(waitForChange(watcher, brdf, changed), 0.0);
    std::vector<std::string> rebuilt = f.renderer->reloadChangedPrograms(changed);
    EXPECT_TRUE(contains(rebuilt, "lighting/smooth"));
    EXPECT_FALSE(contains(rebuilt, "gbuffer"));
    EXPECT_FALSE(contains(rebuilt, "tonemap"));
    // A file no program uses rebuilds nothing.
    EXPECT_TRUE(f.renderer->reloadChangedPrograms({copy.dir() / "glints" / "README.md"}).empty());
}

TEST(FileWatcher, ModificationTimeFallbackSeesWritesAndRenames) {
    TempShaderCopy copy("watch-mtime");
    FileWatcher watcher(copy.dir(), 40ms, FileWatcher::Mode::ModificationTime);
    EXPECT_EQ(watcher.mode(), FileWatcher::Mode::ModificationTime);
    auto quiet = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - quiet < 250ms) {
        EXPECT_TRUE(watcher.poll().empty()) << "no change, no report";
        std::this_thread::sleep_for(10ms);
    }
    fs::path file = copy.dir() / "image/tonemap.frag";
    std::vector<fs::path> changed;
    writeFile(file, readTextFile(file) + "\n", false);
    double latency = waitForChange(watcher, file, changed);
    ASSERT_GE(latency, 0.0);
    EXPECT_LT(latency, 500.0);
    writeFile(file, readTextFile(file) + "\n", true);
    EXPECT_GE(waitForChange(watcher, file, changed), 0.0);
}

TEST(FileWatcher, DebounceMergesBurstsAndWatchesNewFolders) {
    TempShaderCopy copy("watch-debounce");
    FileWatcher watcher(copy.dir(), 80ms);
    fs::path file = copy.dir() / "common/fullscreen.vert";
    std::string text = readTextFile(file);
    auto written = std::chrono::steady_clock::now();
    writeFile(file, text + "\n", false);
    std::this_thread::sleep_for(20ms);
    std::vector<fs::path> early = watcher.poll();
    // On a loaded machine the sleep may outlast the debounce; only then may the change already be reported.
    if (std::chrono::steady_clock::now() - written < 70ms) EXPECT_TRUE(early.empty()) << "reported before the debounce interval";
    writeFile(file, text + "\n\n", true);
    std::vector<fs::path> changed;
    ASSERT_GE(waitForChange(watcher, file, changed), 0.0);
    EXPECT_EQ(std::count(changed.begin(), changed.end(), fs::canonical(file)), 1);
    EXPECT_TRUE(watcher.poll().empty());

    fs::create_directory(copy.dir() / "newfolder");
    std::this_thread::sleep_for(20ms);
    watcher.poll();  // picks up the new folder's watch
    fs::path nested = copy.dir() / "newfolder" / "x.glsl";
    writeFile(nested, "// new\n", false);
    EXPECT_GE(waitForChange(watcher, nested, changed), 0.0);
}

}  // namespace
}  // namespace glimmer
