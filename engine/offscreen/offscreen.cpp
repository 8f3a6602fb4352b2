#include "offscreen/offscreen.h"

#include "core/clock.h"
#include "core/files.h"
#include "core/log.h"
#include "glints/methods.h"
#include "offscreen/render_stats.h"
#include "offscreen/supersample.h"
#include "render/image/upscale.h"
#include "scene/scene_loader.h"

namespace glimmer {

OffscreenSession::OffscreenSession(const RenderRequest& request) {
    Stopwatch clock;
    baseScene_ = loadScene(request.scene);
    sceneLoadMs_ = clock.elapsedMs();
    baseScene_.camera(request.camera);  // validate --camera before creating a context
    findGlintMethod(request.settings.method);
    context_ = createHeadlessContext(request.backend);
    scene_ = baseScene_;
    applySceneOverrides(request.settings, scene_);
    gpuScene_ = std::make_unique<GpuScene>(scene_);
    clock.restart();
    renderer_ = std::make_unique<Renderer>(request.shaderRoot.empty() ? defaultShaderDir() : request.shaderRoot,
                                           request.settings);
    programBuildMs_ = clock.elapsedMs();
    applyEnvironment(request);   // precompute now, so frame timings do not include it
}

void OffscreenSession::applyEnvironment(const RenderRequest& request) {
    if (request.environment) scene_.environment = *request.environment;
    renderer_->prepareEnvironment(scene_, request.environment ? "--env" : "scene environment");
}

OffscreenSession::~OffscreenSession() {
    // GL objects must die while the context is current.
    if (context_) context_->makeCurrent();
    renderer_.reset();
    gpuScene_.reset();
}

RenderResult OffscreenSession::render(const RenderRequest& request) {
    // aa=ssaa: the same render at N x the size, box-filtered down (a reference for the anti-aliasing measurements).
    if (int(request.settings.value(param::aa)) == 2 && request.settings.debugView == 0)
        return image::supersampledRender(request, [this](const RenderRequest& r) { return render(r); });
    context_->makeCurrent();
    scene_ = baseScene_;
    applySceneOverrides(request.settings, scene_);
    gpuScene_->updateMaterialsAndLights(scene_);
    renderer_->setSettings(request.settings);
    applyEnvironment(request);

    View view{.camera = request.cameraOverride ? *request.cameraOverride : scene_.camera(request.camera),
              .width = std::max(1, int(std::lround(request.renderScale * float(request.width)))),
              .height = std::max(1, int(std::lround(request.renderScale * float(request.height)))),
              .outputWidth = request.width,
              .outputHeight = request.height};
    // Monte Carlo IBL modes: each frame is the mean of `spp` estimates (sample 0 renders the G-buffer).
    RenderTimings timings;
    for (int frame = 0; frame < std::max(request.frames, 1); ++frame) {
        FrameClock clock;
        renderer_->renderAccumulated(scene_, *gpuScene_, view, request.spp, true);
        glFinish();
        timings.add(clock);
        if (frame == 0) timings.firstPasses = renderer_->passTimings();   // every shadow map; later frames reuse them
    }
    RenderResult result;
    result.width = request.width;
    result.height = request.height;
    result.hdr = renderer_->readHdr();
    result.display = renderer_->readDisplay();
    const View& rendered = renderer_->lastView();
    if (rendered.postWidth != request.width || rendered.postHeight != request.height) {   // no TAA upsampling
        result.hdr = catmullRomUpscale(result.hdr, rendered.postWidth, rendered.postHeight, request.width, request.height);
        result.display =
            catmullRomUpscale(result.display, rendered.postWidth, rendered.postHeight, request.width, request.height);
    }
    result.stats = renderStats({.request = request,
                                .context = *context_,
                                .scene = scene_,
                                .gpuScene = *gpuScene_,
                                .renderer = *renderer_,
                                .timings = timings,
                                .hdr = result.hdr,
                                .sceneLoadMs = sceneLoadMs_,
                                .programBuildMs = programBuildMs_});
    return result;
}

RenderResult renderOffscreen(const RenderRequest& request) {
    OffscreenSession session(request);
    return session.render(request);
}

}  // namespace glimmer
