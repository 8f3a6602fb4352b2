// The split-screen comparison (`view --split`, keys B and Shift+B): the left part shows the window's method, the
// right part another one, rendered by a second renderer with the same scene, camera and settings; a divider the
// mouse drags separates them.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "app/walkthrough/frame_driver.h"
#include "app/walkthrough/window_resolution.h"
#include "render/renderer.h"
#include "ui/ui.h"

namespace glimmer {

class SplitView {
public:
    // `method`: the right side's method (--split), which also turns the split on; `position`: the divider's place.
    SplitView(const std::optional<std::string>& method, float position);

    bool enabled() const { return enabled_; }
    void toggle() { enabled_ = !enabled_; }
    // The right side's next method in the table; turns the split on.
    void cycleMethod(const std::string& leftMethod);
    // The method shown on the right: the one chosen, else the first method differing from `leftMethod`.
    std::string rightMethod(const std::string& leftMethod) const;
    // A reloaded user method file renamed its method.
    void renameMethod(const std::string& from, const std::string& to);

    // The divider follows the mouse while the left button that grabbed it (within a few pixels, outside the panel)
    // is held; the panel must not see that drag, so `input` loses the button then.
    void dragDivider(ui::Input& input, bool leftPressed, bool pointerOverUi, int width);

    // Renders the right part (`left`'s settings with the other method) and presents it over the columns right of the
    // divider in `target`, then draws a 2-pixel divider line. Costs a second frame, not a second precomputation: the
    // right renderer reads `left`'s environment and reflection probes (left renders first). A method that fails to build
    // turns the split off and returns the error.
    std::optional<std::string> render(Renderer& left, const FrameDriver& frames, WindowResolution& resolution,
                                      GLuint target, const Scene& scene, const GpuScene& gpuScene,
                                      const Camera& camera, int width, int height);
    // Method names on both sides of the divider, at the top.
    void drawLabels(ui::Context& ui, const std::string& leftMethod, int width, float margin, float line) const;

    // The second renderer, once the split has been shown (hot reload rebuilds its programs too).
    Renderer* renderer() { return renderer_.get(); }

private:
    bool enabled_ = false, dragging_ = false;
    std::string method_;      // "" = first method differing from the left one
    float fraction_ = 0.5f;   // divider as a fraction of the width
    std::unique_ptr<Renderer> renderer_;   // created on the first split frame
};

}  // namespace glimmer
