#include "app/walkthrough/window_resolution.h"

#include <algorithm>
#include <cstdio>
#include <numeric>

namespace glimmer {

WindowResolution::WindowResolution(const std::filesystem::path& shaderRoot, bool softwareRenderer, bool headless,
                                   bool likeRender, std::optional<float> renderScale,
                                   std::optional<float> targetFps)
    : upscale_(shaderRoot) {
    bool defaults = softwareRenderer && !likeRender;
    float fps = targetFps ? *targetFps : (defaults && !renderScale && !headless ? kSoftwareTargetFps : 0.0f);
    float scale = renderScale ? *renderScale : (defaults ? kSoftwareStartScale : 1.0f);
    control_ = DynamicResolution(scale, fps);
}

void WindowResolution::addFrame(double frameMs, unsigned stillFrames) {
    times_.add(frameMs);
    scales_.push_back(control_.scale());
    if (stillFrames >= kStillHoldFrames) return;
    if (control_.addFrame(frameMs)) ++changes_;
}

void WindowResolution::present(const Renderer& renderer, GLuint target, int windowW, int windowH, int fromColumn) {
    // Under TAA upsampling the display image already has the window's size and this is a copy.
    const View& view = renderer.lastView();
    upscale_.draw(renderer.displayTexture(), renderer.displayFramebuffer(), view.postWidth, view.postHeight, target,
                  windowW, windowH, fromColumn);
}

std::string WindowResolution::statsText() const {
    char text[128];
    int n = std::snprintf(text, sizeof text, "p50 %.1f p95 %.1f ms  scale %.2f", times_.recentPercentile(0.5),
                          times_.recentPercentile(0.95), double(control_.scale()));
    if (control_.adaptive() && n > 0 && size_t(n) < sizeof text)
        std::snprintf(text + n, sizeof text - size_t(n), " (target %g fps)", double(control_.targetFps()));
    return text;
}

nlohmann::json WindowResolution::statsJson() const {
    const std::vector<double>& all = times_.all();
    double mean = all.empty() ? 0.0 : std::accumulate(all.begin(), all.end(), 0.0) / double(all.size());
    double median = times_.runPercentile(0.5);
    auto [lo, hi] = scales_.empty() ? std::make_pair(scales_.end(), scales_.end())
                                    : std::minmax_element(scales_.begin(), scales_.end());
    return {
        {"frames_measured", all.size()},
        {"frame_ms", {{"median", median}, {"p95", times_.runPercentile(0.95)}, {"mean", mean},
                      {"min", times_.runPercentile(0.0)}, {"max", times_.runPercentile(1.0)}}},
        {"fps_at_median", median > 0.0 ? 1000.0 / median : 0.0},
        {"render_scale", {{"final", control_.scale()},
                          {"min", scales_.empty() ? 0.0 : *lo}, {"max", scales_.empty() ? 0.0 : *hi},
                          {"median", percentile(scales_, 0.5)}, {"changes", changes_},
                          {"target_fps", control_.targetFps()}, {"adaptive", control_.adaptive()}}},
        {"frame_times_ms", all},
    };
}

}  // namespace glimmer
