// The window's resolution handling: the scene renders at the dynamic render scale (render/dynamic_resolution.h),
// the display image is upscaled to the window (render/image/upscale.h) before the UI is drawn at native resolution, and
// frame times are kept for percentiles (strip and `view --stats`). Glint footprints and UV derivatives are those of
// the internal resolution by construction: the G-buffer and lighting passes run at the internal size.
#pragma once
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "core/frame_times.h"
#include "render/dynamic_resolution.h"
#include "render/renderer.h"
#include "render/image/upscale.h"

namespace glimmer {

class WindowResolution {
public:
    // The start scale is where the atrium settles on a 2-core llvmpipe machine at 1280x720: a higher start costs many
    // slow frames on the way down, as the controller changes the scale by at most 15% every 4 frames
    // (docs/measurements.md); faster machines raise it from there.
    static constexpr float kSoftwareTargetFps = 12.0f, kSoftwareStartScale = 0.25f;

    // Defaults per renderer: software renderers adapt towards kSoftwareTargetFps from kSoftwareStartScale; a
    // `headless` run that writes screenshots holds kSoftwareStartScale, the floor where the atrium sits on two cores, so that its
    // images do not depend on the machine's speed; `likeRender` renders at scale 1, like `glimmer render`.
    // GPUs render at scale 1. Flags override.
    WindowResolution(const std::filesystem::path& shaderRoot, bool softwareRenderer, bool headless,
                     bool likeRender, std::optional<float> renderScale, std::optional<float> targetFps);

    // One frame's wall time (ms, frames after the first); adapts the scale, except once the view has been still
    // for kStillHoldFrames frames (`stillFrames`: consecutive frames with the same camera and settings): a scale
    // change resets the TAA history, so a controller that kept adjusting made a still camera's image change. It
    // adapts again as soon as the camera moves or a setting changes.
    void addFrame(double frameMs, unsigned stillFrames = 0);
    static constexpr unsigned kStillHoldFrames = 24;
    void internalSize(int windowW, int windowH, int& w, int& h) const { control_.internalSize(windowW, windowH, w, h); }
    // The renderer's display image (internal size) to `target` (window size), from column `fromColumn` on.
    void present(const Renderer& renderer, GLuint target, int windowW, int windowH, int fromColumn = 0);

    float scale() const { return control_.scale(); }
    // "p50 83.1 p95 97.0 ms  scale 0.62 (target 12 fps)" over the recent frames.
    std::string statsText() const;
    // The run's frame times: count, median, p95, mean, fps at the median, scale range.
    nlohmann::json statsJson() const;
    const std::vector<std::filesystem::path>& dependencies() const { return upscale_.dependencies(); }

private:
    DynamicResolution control_;
    UpscalePass upscale_;
    FrameTimes times_;
    std::vector<double> scales_;   // per measured frame
    int changes_ = 0;
};

}  // namespace glimmer
