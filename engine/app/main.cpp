// glimmer: a deferred OpenGL 4.5 engine for real-time glints. Subcommands: render, view, bench.
#include <cstdio>
#include <cstring>
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
    "  main     the window when a display exists, else an offscreen render of the default scene\n";

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h") {
        std::fputs(kUsage, args.empty() ? stderr : stdout);
        return args.empty() ? 2 : 0;
    }
    std::string command = args[0];
    args.erase(args.begin());
    try {
        if (command == "render") return glimmer::runRenderCommand(args);
        if (command == "view") return glimmer::runViewCommand(args);
        if (command == "bench") return glimmer::runBenchCommand(args);
        if (command == "main") {
            if (glimmer::GlfwWindow::displayAvailable()) return glimmer::runViewCommand(args);
            std::vector<std::string> renderArgs = {"--out", "glimmer-default.png"};
            renderArgs.insert(renderArgs.end(), args.begin(), args.end());
            return glimmer::runRenderCommand(renderArgs);
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
