// The loading frame of `glimmer view` (issue 39): the window's first frame comes within a second of it opening,
// before any precomputation, and each later step of the start-up (shaders, collision mesh, environment maps,
// reflection probes, glint data, ambient occlusion, the first picture) redraws it with the step in progress, the
// steps done with their times and a progress bar, so the window is never black and never silent. Drawn by the
// engine's UI renderer alone (one small program, built first).
//
// Start-up times are logged ("view: loading frame at ... s after process start (... s after the window opened);
// first picture at ..."), which docs/window.md's measurements read. GLIMMER_LOADING_SCREENSHOTS=DIR writes each
// loading frame as DIR/loading-NN.png (the window test checks them).
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/clock.h"
#include "platform/glfw_window.h"
#include "ui/ui_renderer.h"

namespace glimmer {

// Seconds since this process started (Linux /proc; 0 where unavailable).
double processAgeSeconds();

class LoadingScreen {
public:
    // The start-up's steps, in order (the progress bar counts them).
    enum Step { Shaders, Collision, Environment, Probes, GlintData, AmbientOcclusion, FirstPicture, kStepCount };

    // `window` has just opened; `sceneName` titles the frame. Records the window's opening time.
    LoadingScreen(GlfwWindow& window, std::string sceneName);
    // Draws the loading frame with `step` in progress (and every earlier step done) and swaps it to the window;
    // a step at or before the current one draws nothing (the renderer reports every pass of every frame).
    void show(Step step, ui::UiRenderer& ui);
    // The step a frame-list pass's prepare() belongs to (Renderer's prepare listener), or nullopt for passes that
    // prepare nothing slow.
    static std::optional<Step> stepOfPass(const std::string& passName);
    // The first picture is on screen: logs the start-up times (once).
    void finish();
    bool finished() const { return finished_; }

private:
    void draw(ui::UiRenderer& ui);

    GlfwWindow& window_;
    std::string sceneName_;
    double windowOpenedAt_ = 0.0;       // process age when the window opened
    Stopwatch sinceWindow_;
    int current_ = -1;                  // the step in progress
    std::vector<double> stepStartMs_;   // since the window opened, per step started
    int framesDrawn_ = 0;
    double firstFrameAt_ = -1.0;        // process age when the first loading frame was swapped
    bool finished_ = false;
    std::optional<std::filesystem::path> screenshotDir_;
};

}  // namespace glimmer
