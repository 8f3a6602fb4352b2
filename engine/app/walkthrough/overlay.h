// What the window writes over the picture besides the panel: shader and method errors (shown even with the UI
// hidden: the user is looking at the picture, not at the log), the stats strip at the bottom, and transient notices
// in the top-right corner.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "render/renderer.h"
#include "ui/ui.h"

namespace glimmer {

std::string twoDecimals(double value);   // "%.2f"

// The gap between the overlay's boxes and the window's edge, in pixels, at the UI's scale.
inline float overlayMargin(const ui::Context& ui) { return float(4 * ui.scale()); }

// The window's side of the stats strip; the renderer gives the rest (pass timers, IBL mode, last edit).
struct WindowStatus {
    double frameMs = 0.0;        // smoothed frame time
    std::string resolution;      // WindowResolution::statsText()
    glm::vec3 position{0.0f};
    float moveSpeed = 0.0f;
    bool vsync = false;
    uint32_t sampleIndex = 0;    // accumulation sample of Monte Carlo IBL modes
    bool mouseCaptured = false;
    bool softwareRenderer = false;
    // An edit (panel, keys, hot reload) happened: only then are the on-demand passes that ran "the last edit's"
    // (at start-up they are the first build, not an edit).
    bool edited = false;
};

struct StatsLine {
    std::string text;
    bool dim = false;
};

class Overlay {
public:
    // A notice shown for a few seconds from `now` (frame clock).
    void notify(const std::string& text, double now);

    // The stats strip: frame time and GPU pass timers (on their own line when they do not fit beside it), the
    // renderer note and camera, and the passes of the last material edit while there are any.
    static std::vector<StatsLine> statsLines(const Renderer& renderer, const WindowStatus& status, float available,
                                             int uiScale);
    // The error box, just above the strip (`statsHeight` tall; 0 with the UI hidden).
    static void drawErrors(ui::Context& ui, const std::vector<std::string>& errors, int width, int height,
                           float statsHeight);
    // The strip, and the notice while it lasts.
    void drawStats(ui::Context& ui, const std::vector<StatsLine>& stats, int width, int height, float statsHeight,
                   double now) const;

private:
    std::string message_;
    double messageUntil_ = 0.0;
};

}  // namespace glimmer
