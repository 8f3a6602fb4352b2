// ibl::SceneCapture through a renderer of its own with default settings (created on first use): what the IBL
// modes' per-object environment maps see.
#pragma once
#include <filesystem>
#include <memory>

#include "environment/ibl/scene_capture.h"

namespace glimmer {

class Renderer;

class RendererCapture : public ibl::SceneCapture {
public:
    explicit RendererCapture(std::filesystem::path shaderRoot);
    ~RendererCapture() override;
    std::vector<std::vector<float>> renderHdr(const Scene& scene, const std::vector<Camera>& cameras,
                                              int size) override;

private:
    std::filesystem::path shaderRoot_;
    std::unique_ptr<Renderer> renderer_;
};

}  // namespace glimmer
