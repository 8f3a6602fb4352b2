// glimmer view: the walkthrough window (engine/app/walkthrough/). `--frames N --screenshot FILE` renders N
// frames and exits (tests run it under xvfb-run); with --hide-ui that image equals `glimmer render`.
#include <cstdio>
#include <cstdlib>

#include "app/commands.h"
#include "app/common_options.h"
#include "app/walkthrough/walkthrough.h"
#include "core/cli.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "glints/methods.h"
#include "glints/user/user_methods.h"
#include "ui/input_script.h"

namespace glimmer {

static const char* kViewHelp =
    "usage: glimmer view [--scene NAME|PATH] [--camera NAME] [--size WxH] [--method NAME] [--set KEY=VALUE ...]\n"
    "                    [--env PATH|none|procedural|constant:R,G,B] [--ibl MODE] [--spp N] [--aov NAME]\n"
    "                    [--shader-dir DIR] [--no-vsync] [--hide-ui] [--split METHOD [--split-at F]]\n"
    "                    [--method-file PATH.glsl ...]\n"
    "                    [--path CAMERA_PATH.json] [--input-script FILE]\n"
    "                    [--render-scale F] [--target-fps FPS] [--walkthrough] [--stats]\n"
    "                    [--frames N --screenshot FILE.png|FILE.exr [--screenshot-at FRAME:FILE ...]]\n"
    "                    [--like-render]\n"
    "  Defaults: the atrium with deliot2023. Scenes whose camera stands on a floor start walking (eye 1.7 m,\n"
    "  gravity, steps up to 0.35 m, collision); F toggles flying (free, no collision).\n"
    "  --render-scale F   render at F x the window (0.25 .. 1), resolved to it by TAA upsampling (aa=taa) or\n"
    "                     upscaled (Catmull-Rom, aa=off) for display\n"
    "  --target-fps FPS   adapt the render scale to hold FPS (0: fixed scale); default 12 on software\n"
    "                     renderers (llvmpipe), off on GPUs\n"
    "  --walkthrough      play the camera path (key P) from the first frame\n"
    "  --method-file PATH.glsl  a user glint method (docs/user_methods.md), edited live like the built-ins\n"
    "  --stats            print frame times (median, p95) as JSON at exit\n"
    "  --frames N --screenshot FILE  render N frames with the window's defaults (TAA, bloom, auto exposure; on\n"
    "                     software renderers render scale 0.25, held fixed) and write the last: the player's image\n"
    "  --screenshot-at FRAME:FILE  also write the image after frame FRAME (1-based, up to N); repeatable\n"
    "  --like-render  use `glimmer render`'s defaults instead (scale 1, no TAA): with --hide-ui the\n"
    "                     screenshot equals `glimmer render`'s image\n"
    "  WASD move, Q/E down/up (flying), Shift faster, wheel speed, right mouse button (or C) looks around,\n"
    "  1-9 scene cameras, P plays the camera path (the recorded one, else the scene's cameras), R records a path\n"
    "  (saved to --path, else <scene>.path.json beside the scene), M/N/I cycle method/debug view/IBL mode,\n"
    "  V vsync, H hide UI, B split-screen comparison (Shift+B: next right-hand method; drag the divider),\n"
    "  Monte Carlo IBL modes accumulate samples while the camera is still.\n"
    "  arrows + Enter drive the panel, F5 reload shaders, F12 screenshot (Shift+F12: EXR), Esc quit.\n"
    "  --input-script replays timed key events (see docs/window.md) for tests and recordings.\n";

int runViewCommand(const std::vector<std::string>& argList) {
    ArgReader args("view", argList);
    if (args.flag("--help")) { std::fputs(kViewHelp, stdout); return 0; }
    ViewOptions options;
    options.request = readCommonRenderOptions(args, "atrium", "deliot2023");
    args.value("--backend");  // accepted for symmetry; the window always uses GLFW
    options.request.width = 1280;
    options.request.height = 720;
    if (auto size = args.value("--size")) parseSize(*size, "--size", options.request.width, options.request.height);
    options.frameLimit = args.intValue("--frames", 0, 0, 1 << 30);
    options.screenshot = args.value("--screenshot");
    for (const std::string& at : args.values("--screenshot-at")) {
        size_t colon = at.find(':');
        char* end = nullptr;
        long frame = colon == std::string::npos ? 0 : std::strtol(at.c_str(), &end, 10);
        if (colon == std::string::npos || colon == 0 || end != at.c_str() + colon || frame < 1 ||
            frame > options.frameLimit || colon + 1 == at.size())
            throw UsageError("--screenshot-at: '" + at + "' is not FRAME:FILE with FRAME in [1, --frames]");
        std::string file = at.substr(colon + 1);
        imageFormatForPath(file, "--screenshot-at");
        checkOutputPath(file, "--screenshot-at");
        options.frameScreenshots.push_back({int(frame), file});
    }
    options.likeRender = args.flag("--like-render");
    options.hideUi = args.flag("--hide-ui");
    options.vsync = !args.flag("--no-vsync");
    auto readFloat = [&](const char* flag, float lo, float hi) -> std::optional<float> {
        auto text = args.value(flag);
        if (!text) return std::nullopt;
        char* end = nullptr;
        float v = std::strtof(text->c_str(), &end);
        if (text->empty() || *end != '\0' || !(v >= lo && v <= hi)) {
            char range[64];
            std::snprintf(range, sizeof range, "[%g, %g]", double(lo), double(hi));
            throw UsageError(std::string(flag) + ": '" + *text + "' is not a number in " + range);
        }
        return v;
    };
    options.renderScale = readFloat("--render-scale", 0.25f, 1.0f);
    options.targetFps = readFloat("--target-fps", 0.0f, 1000.0f);
    options.playWalkthrough = args.flag("--walkthrough");
    options.printStats = args.flag("--stats");
    if (auto split = args.value("--split")) options.splitMethod = resolveGlintMethod(*split, "--split");
    if (auto at = args.value("--split-at")) {
        char* end = nullptr;
        options.splitPosition = std::strtof(at->c_str(), &end);
        if (at->empty() || *end != '\0' || !(options.splitPosition >= 0.0f && options.splitPosition <= 1.0f))
            throw UsageError("--split-at: '" + *at + "' is not a number in [0, 1]");
        if (!options.splitMethod) throw UsageError("--split-at: only with --split METHOD");
    }
    if (auto script = args.value("--input-script")) {
        ui::readInputScript(*script);  // a bad script fails here, before the window opens
        options.inputScript = *script;
    }
    options.pathFile = args.value("--path");
    args.finish();
    // The window's defaults (TAA, bloom, auto exposure, the software switches: ui/window_defaults.h) are applied
    // where the renderer is known (app/walkthrough/window_settings.h), to headless --frames runs too, so that tests
    // and measurements see the player's image; --like-render keeps `glimmer render`'s defaults instead.
    if (options.screenshot) {
        imageFormatForPath(*options.screenshot, "--screenshot");
        checkOutputPath(*options.screenshot, "--screenshot");  // before the window opens and renders
    }
    if (options.screenshot && options.frameLimit == 0)
        throw UsageError("--screenshot needs --frames N (interactive screenshots: F12)");
    return runWalkthroughWindow(options);
}

}  // namespace glimmer
