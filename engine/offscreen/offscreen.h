// One offscreen render, start to finish: context, scene, renderer, readback. Used by `glimmer render`,
// batch captures and the tests (which call it in-process).
#pragma once
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "platform/context.h"
#include "render/renderer.h"
#include "render/settings.h"

namespace glimmer {

struct RenderRequest {
    std::string scene = "plane90";     // built-in name or file path
    std::string camera;                // "" = the scene's first camera
    std::optional<Camera> cameraOverride;  // when set, replaces `camera` (camera paths: bench --temporal)
    int width = 512, height = 512;
    Backend backend = Backend::Egl;
    RenderSettings settings;
    std::filesystem::path shaderRoot;  // empty = defaultShaderDir()
    int frames = 1;                    // frames rendered (the last one is read back)
    // The scene renders at round(renderScale x size) (at least 1 pixel) and the result has `width` x `height`:
    // with aa=taa TAA resolves to it (TAA upsampling), otherwise the display and HDR images are upscaled with
    // the window's Catmull-Rom filter (render/image/upscale.h). 1: no scaling.
    float renderScale = 1.0f;
    int spp = 1;                       // samples per pixel for accumulating integrators (environment lighting)
    // --env: overrides Scene::environment ("" or "procedural", "none", "constant:R,G,B", or an image path).
    std::optional<std::string> environment;
};

struct RenderResult {
    int width = 0, height = 0;
    std::vector<float> hdr;            // RGBA32F, bottom-up: radiance or the debug view
    std::vector<uint8_t> display;      // RGBA8 sRGB, bottom-up
    nlohmann::json stats;              // what --stats prints
};

// A reusable headless session (context + loaded scene + renderer) for several renders of one scene.
class OffscreenSession {
public:
    explicit OffscreenSession(const RenderRequest& request);
    ~OffscreenSession();
    RenderResult render(const RenderRequest& request);
    GLContext& context() { return *context_; }
    Scene& scene() { return scene_; }
    Renderer& renderer() { return *renderer_; }

private:
    std::unique_ptr<GLContext> context_;
    Scene baseScene_, scene_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<Renderer> renderer_;
    void applyEnvironment(const RenderRequest& request);
    double sceneLoadMs_ = 0.0, programBuildMs_ = 0.0;
};

RenderResult renderOffscreen(const RenderRequest& request);

}  // namespace glimmer
