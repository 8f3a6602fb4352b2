#include "app/walkthrough/window_settings.h"

#include "ui/window_defaults.h"

namespace glimmer {

RenderSettings windowRenderSettings(const RenderSettings& requested, bool softwareRenderer, bool likeRender) {
    RenderSettings settings = requested;
    if (!likeRender) ui::applyWindowDefaults(settings, softwareRenderer);
    return settings;
}

}  // namespace glimmer
