// ibl::SceneCapture through a renderer of its own with default settings (created on first use), sharing the
// environment of the renderer it serves: what the IBL modes' per-object environment maps see. Each map face is a
// view rendered by Renderer::renderView like any other.
#pragma once
#include <filesystem>
#include <memory>

#include "environment/ibl/scene_capture.h"

namespace glimmer {

class Environment;
class Renderer;

class RendererCapture : public ibl::SceneCapture {
public:
    // `environment`: the served renderer's, shared (null: the capture renderer prepares its own from the scene).
    explicit RendererCapture(std::filesystem::path shaderRoot, Environment* environment = nullptr);
    ~RendererCapture() override;
    std::vector<std::vector<float>> renderHdr(const Scene& scene, const std::vector<Camera>& cameras,
                                              int size) override;

private:
    std::filesystem::path shaderRoot_;
    Environment* environment_;
    std::unique_ptr<Renderer> renderer_;
};

}  // namespace glimmer
