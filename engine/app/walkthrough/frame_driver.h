// Every renderView call of the window, and the accumulation of Monte Carlo IBL modes: their estimates average while
// camera, size, scene and settings stay as they were; any change starts a new mean. The one place where the window
// asks the renderer for a frame.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "render/renderer.h"
#include "render/view.h"

namespace glimmer {

class FrameDriver {
public:
    // The frame of the window's (left) view at the render size `renderW` x `renderH`, resolved for an output of
    // `outputW` x `outputH` (TAA upsampling). `settingsVersion` changes with every edit that restarts the mean.
    void render(Renderer& renderer, const Scene& scene, const GpuScene& gpuScene, const Camera& camera, int outputW,
                int outputH, int renderW, int renderH, uint64_t settingsVersion);
    // A second view of the same frame (the split screen's right side): it accumulates in step with the first.
    void renderAlongside(Renderer& renderer, const Scene& scene, const GpuScene& gpuScene, const Camera& camera,
                         int outputW, int outputH, int renderW, int renderH) const;
    uint32_t sampleIndex() const { return sampleIndex_; }

private:
    void updateAccumulation(Renderer& renderer, const Camera& camera, int width, int height, uint64_t settingsVersion);

    uint32_t sampleIndex_ = 0;
    uint64_t accumulatedSettingsVersion_ = ~uint64_t(0);
    glm::mat4 accumulatedView_{0.0f};
    int accumulatedWidth_ = 0, accumulatedHeight_ = 0;
};

}  // namespace glimmer
