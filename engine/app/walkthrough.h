// The walkthrough window behind `glimmer view`: input (WASD + mouse look, keys), the control panel, shader hot
// reload, screenshots, and one frame = Renderer::render + the UI overlay presented through the window.
#pragma once
#include <optional>
#include <string>

#include "offscreen/offscreen.h"

namespace glimmer {

struct ViewOptions {
    RenderRequest request;                  // scene, camera, size, method, --set, --aov, --shader-dir
    int frameLimit = 0;                     // > 0: render this many frames, write the screenshot, exit
    std::optional<std::string> screenshot;  // .png (window image) or .exr (HDR radiance / debug view)
    bool hideUi = false;
    bool vsync = true;
    // Split-screen comparison (key B toggles, Shift+B cycles the right-hand method, drag the divider): the left
    // part shows request.settings.method, the right part `splitMethod`, both rendered every frame.
    std::optional<std::string> splitMethod;
    float splitPosition = 0.5f;             // divider as a fraction of the width
    std::optional<std::string> inputScript; // --input-script: timed key events replayed (ui/input_script.h)
    std::optional<std::string> pathFile;    // --path: camera path played by P and written by R
    // Resolution (render/dynamic_resolution.h): unset = defaults (software renderers: target 12 fps with dynamic
    // resolution from scale 0.5, except for --screenshot runs, which stay at scale 1; GPUs: scale 1).
    std::optional<float> renderScale;       // --render-scale: start (or fixed) scale in [0.25, 1]
    std::optional<float> targetFps;         // --target-fps: > 0 adapts the scale, 0 keeps it fixed
    bool printStats = false;                // --stats: frame-time JSON on stdout at exit
    bool playWalkthrough = false;           // --walkthrough: play the camera path (key P) from the first frame
};

int runWalkthroughWindow(const ViewOptions& options);

}  // namespace glimmer
