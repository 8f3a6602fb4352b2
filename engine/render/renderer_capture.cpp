#include "render/renderer_capture.h"

#include "render/gpu_scene.h"
#include "render/renderer.h"

namespace glimmer {

RendererCapture::RendererCapture(std::filesystem::path shaderRoot, Environment* environment)
    : shaderRoot_(std::move(shaderRoot)), environment_(environment) {}
RendererCapture::~RendererCapture() = default;

std::vector<std::vector<float>> RendererCapture::renderHdr(const Scene& scene, const std::vector<Camera>& cameras,
                                                           int size) {
    if (!renderer_) {
        // The per-object maps see the distant environment only, as before the reflection probes: a map with
        // probes would be a second, different local-reflection scheme inside the regular-sampling comparison.
        RenderSettings settings;
        settings.apply("probes.enabled=0");
        renderer_ = std::make_unique<Renderer>(shaderRoot_, settings, FrameKind::Full, environment_);
    }
    GpuScene gpuScene(scene);
    std::vector<std::vector<float>> images;
    for (const Camera& camera : cameras) {
        renderer_->renderView(scene, gpuScene, camera, size, size);
        images.push_back(renderer_->readHdr());
    }
    return images;
}

}  // namespace glimmer
