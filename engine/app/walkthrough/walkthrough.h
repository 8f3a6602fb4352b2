// The walkthrough window behind `glimmer view`. The window loop (window_loop.cpp) ties together the parts in this
// folder, one job each: input.* (keys, mouse, input scripts), camera_motion.* (walking, flying, camera paths),
// method_files.* (shader hot reload, user method files), split_view.* (two methods side by side), frame_driver.*
// (the renderer calls and the accumulation of Monte Carlo IBL modes), overlay.* (errors, stats strip, notices),
// present.* (the window image and screenshots), window_settings.* and window_resolution.* (the window's defaults
// and render scale).
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "offscreen/offscreen.h"

namespace glimmer {

struct ViewOptions {
    RenderRequest request;                  // scene, camera, size, method, --set, --aov, --shader-dir
    int frameLimit = 0;                     // > 0: render this many frames, write the screenshot, exit
    std::optional<std::string> screenshot;  // .png (window image) or .exr (HDR radiance / debug view)
    std::vector<std::pair<int, std::string>> frameScreenshots;  // --screenshot-at: (1-based frame, file)
    // --like-render: `glimmer render`'s settings and scale 1 instead of the window's defaults, so that a
    // --hide-ui screenshot equals the offscreen render (tests that compare the two).
    bool likeRender = false;
    bool hideUi = false;
    bool vsync = true;
    // Split-screen comparison (key B toggles, Shift+B cycles the right-hand method, drag the divider): the left
    // part shows request.settings.method, the right part `splitMethod`, both rendered every frame.
    std::optional<std::string> splitMethod;
    float splitPosition = 0.5f;             // divider as a fraction of the width
    std::optional<std::string> inputScript; // --input-script: timed key events replayed (ui/input_script.h)
    std::optional<std::string> pathFile;    // --path: camera path played by P and written by R
    // Resolution (render/dynamic_resolution.h): unset = defaults (software renderers: target 12 fps with dynamic
    // resolution from scale 0.25, held fixed at 0.25 in --frames runs so that their images repeat; scale 1 with
    // --like-render; GPUs: scale 1).
    std::optional<float> renderScale;       // --render-scale: start (or fixed) scale in [0.25, 1]
    std::optional<float> targetFps;         // --target-fps: > 0 adapts the scale, 0 keeps it fixed
    bool printStats = false;                // --stats: frame-time JSON on stdout at exit
    bool playWalkthrough = false;           // --walkthrough: play the camera path (key P) from the first frame
};

int runWalkthroughWindow(const ViewOptions& options);

}  // namespace glimmer
