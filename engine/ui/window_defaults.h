// The settings the window renders with unless --set says otherwise (docs/window.md): the game image (TAA, a little
// bloom, auto exposure) everywhere, and on software renderers (llvmpipe) the per-machine switches that hold its
// frame rate. `glimmer view` applies them to interactive and headless (--frames) runs alike, so a screenshot shows
// what the player sees; `view --like-render` keeps `glimmer render`'s defaults instead. Tools and tests that
// measure the window's image call it too.
#pragma once
#include "render/settings.h"

namespace glimmer::ui {

// The render scale the window starts at: 0.25 on software renderers (where the atrium settles on 2 cores), 1 on
// GPUs (app/window_resolution.h adapts it from there).
float windowStartScale(bool softwareRenderer);

// Sets every window default that `settings` does not set already.
void applyWindowDefaults(RenderSettings& settings, bool softwareRenderer);

}  // namespace glimmer::ui
