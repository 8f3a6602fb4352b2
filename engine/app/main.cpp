// glimmer: a deferred OpenGL 4.5 engine for real-time glints. Subcommands: render, view, bench, check-method, main.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "app/commands.h"
#include "core/error.h"
#include "gl/program.h"
#include "platform/glfw_window.h"

static const char* kUsage =
    "usage: glimmer <command> [options]\n"
    "  render   offscreen render to PNG/EXR (glimmer render --help)\n"
    "  view     the walkthrough window (glimmer view --help)\n"
    "  bench    time renders (glimmer bench --help)\n"
    "  check-method PATH.glsl  run the interface rules on a user glint method (glimmer check-method --help)\n"
    "  main     the window when a display exists, else an offscreen render of the default scene\n"
    "  --version  print the version\n";

static const char* kMainHelp =
    "usage: glimmer main [view or render options]\n"
    "  The default experience: the atrium with Deliot & Belcour 2023 glints. With a display it opens the\n"
    "  walkthrough window (glimmer view --help lists its options and keys); without one it renders the 'court'\n"
    "  camera at 1280x720 to glimmer-default.png (glimmer render --help). Options given replace these defaults.\n";

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h") {
        std::fputs(kUsage, args.empty() ? stderr : stdout);
        return args.empty() ? 2 : 0;
    }
    if (args[0] == "--version" || args[0] == "-V") {
        std::printf("glimmer %s\n", GLIMMER_VERSION);
        return 0;
    }
    std::string command = args[0];
    args.erase(args.begin());
    try {
        if (command == "render") return glimmer::runRenderCommand(args);
        if (command == "view") return glimmer::runViewCommand(args);
        if (command == "bench") return glimmer::runBenchCommand(args);
        if (command == "check-method") return glimmer::runCheckCommand(args);
        if (command == "main") {
            if (std::find(args.begin(), args.end(), "--help") != args.end()) {
                std::fputs(kMainHelp, stdout);
                return 0;
            }
            // The default experience: the atrium with Deliot & Belcour glints (options given override these).
            auto given = [&](const char* flag) { return std::find(args.begin(), args.end(), flag) != args.end(); };
            std::vector<std::string> defaults;
            if (!given("--scene")) defaults.insert(defaults.end(), {"--scene", "atrium"});
            if (!given("--method")) defaults.insert(defaults.end(), {"--method", "deliot2023"});
            if (glimmer::GlfwWindow::displayAvailable()) {
                defaults.insert(defaults.end(), args.begin(), args.end());
                return glimmer::runViewCommand(defaults);
            }
            if (!given("--camera")) defaults.insert(defaults.end(), {"--camera", "court"});
            if (!given("--size")) defaults.insert(defaults.end(), {"--size", "1280x720"});
            if (!given("--out")) defaults.insert(defaults.end(), {"--out", std::filesystem::absolute("glimmer-default.png").string()});
            defaults.insert(defaults.end(), args.begin(), args.end());
            return glimmer::runRenderCommand(defaults);
        }
        std::fprintf(stderr, "glimmer: unknown command '%s'\n%s", command.c_str(), kUsage);
        return 2;
    } catch (const glimmer::UsageError& e) {
        std::fprintf(stderr, "glimmer: %s\n", e.what());
        return 2;
    } catch (const glimmer::Error& e) {
        std::fprintf(stderr, "glimmer: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glimmer: internal error: %s\n", e.what());
        return 3;
    }
}
