// The render settings of the window: the command line's, with the window's own defaults for what it leaves unset.
#pragma once
#include "render/settings.h"

namespace glimmer {

// `requested` with the window's defaults: on software renderers the switches that keep the atrium interactive on
// two cores (texture filtering, half-resolution shadows and AO, TAA and post passes at the render size, geometry
// LOD), and on every renderer the split lighting programs. A --screenshot run keeps the offscreen defaults so that
// its image equals `glimmer render`'s.
RenderSettings windowRenderSettings(const RenderSettings& requested, bool softwareRenderer, bool screenshotRun);

}  // namespace glimmer
