#include "app/walkthrough/frame_driver.h"

namespace glimmer {

void FrameDriver::updateAccumulation(Renderer& renderer, const Camera& camera, int width, int height,
                                     uint64_t settingsVersion) {
    glm::mat4 view = camera.view();
    bool still = view == accumulatedView_ && width == accumulatedWidth_ && height == accumulatedHeight_ &&
                 accumulatedSettingsVersion_ == settingsVersion;
    sampleIndex_ = still && renderer.accumulating() ? sampleIndex_ + 1 : 0;
    accumulatedView_ = view;
    accumulatedWidth_ = width;
    accumulatedHeight_ = height;
    accumulatedSettingsVersion_ = settingsVersion;
}

void FrameDriver::render(Renderer& renderer, const Scene& scene, const GpuScene& gpuScene, const Camera& camera,
                         int outputW, int outputH, int renderW, int renderH, uint64_t settingsVersion) {
    updateAccumulation(renderer, camera, renderW, renderH, settingsVersion);
    // aa=taa below scale 1 resolves to the window size (TAAU).
    View view{.camera = camera, .width = renderW, .height = renderH, .outputWidth = outputW, .outputHeight = outputH,
              .sampleIndex = sampleIndex_};
    renderer.renderView(scene, gpuScene, view);
}

void FrameDriver::renderAlongside(Renderer& renderer, const Scene& scene, const GpuScene& gpuScene,
                                  const Camera& camera, int outputW, int outputH, int renderW, int renderH) const {
    View view{.camera = camera, .width = renderW, .height = renderH, .outputWidth = outputW, .outputHeight = outputH,
              .sampleIndex = sampleIndex_};
    renderer.renderView(scene, gpuScene, view);
}

}  // namespace glimmer
