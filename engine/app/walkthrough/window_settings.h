// The render settings of the window: the command line's, with the window's own defaults for what it leaves unset.
#pragma once
#include "render/settings.h"

namespace glimmer {

// `requested` with the window's defaults (ui/window_defaults.h: the game image, TAA, bloom and auto exposure, the
// split lighting programs, and on software renderers the switches that keep the atrium interactive on two cores),
// for interactive and headless runs alike. `likeRender` (view --like-render) keeps `glimmer render`'s defaults so
// that a screenshot equals its image.
RenderSettings windowRenderSettings(const RenderSettings& requested, bool softwareRenderer, bool likeRender);

}  // namespace glimmer
