#include "offscreen/offscreen.h"

#include <array>
#include <ctime>

#include "core/clock.h"
#include "core/files.h"
#include "core/log.h"
#include "glints/methods.h"
#include "render/aov.h"
#include "offscreen/supersample.h"
#include "render/shadows/shadow_maps.h"
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
    if (int(request.settings.common_("aa")) == 2 && request.settings.debugView == 0)
        return image::supersampledRender(request, [this](const RenderRequest& r) { return render(r); });
    context_->makeCurrent();
    scene_ = baseScene_;
    applySceneOverrides(request.settings, scene_);
    gpuScene_->updateMaterialsAndLights(scene_);
    renderer_->setSettings(request.settings);
    applyEnvironment(request);
    const Camera& camera = request.cameraOverride ? *request.cameraOverride : scene_.camera(request.camera);

    // Monte Carlo IBL modes: each frame is the mean of `spp` estimates (sample 0 renders the G-buffer).
    const int samples = renderer_->accumulating() ? request.spp : 1;
    std::vector<double> frameMs, frameCpuMs;
    std::vector<PassTiming> firstPasses;   // the first frame renders every shadow map; later ones reuse them
    // Process CPU time (every thread, llvmpipe's rasterizer workers included): on a software renderer sharing
    // the machine with other work it is far steadier than the wall clock.
    auto processCpuMs = [] {
        timespec t{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
    };
    const int renderW = std::max(1, int(std::lround(request.renderScale * float(request.width))));
    const int renderH = std::max(1, int(std::lround(request.renderScale * float(request.height))));
    renderer_->setOutputSize(request.width, request.height);
    for (int frame = 0; frame < std::max(request.frames, 1); ++frame) {
        Stopwatch clock;
        double cpuStart = processCpuMs();
        for (int sample = 0; sample < samples; ++sample) {
            renderer_->setSampleIndex(uint32_t(sample));
            renderer_->render(scene_, *gpuScene_, camera, renderW, renderH, sample + 1 == samples);
            if (samples >= 64 && (sample + 1) % (samples / 8) == 0)
                log::info("render: ", sample + 1, " / ", samples, " samples");
        }
        glFinish();
        frameMs.push_back(clock.elapsedMs());
        frameCpuMs.push_back(processCpuMs() - cpuStart);
        if (frame == 0) firstPasses = renderer_->passTimings();
    }
    RenderResult result;
    result.width = request.width;
    result.height = request.height;
    result.hdr = renderer_->readHdr();
    result.display = renderer_->readDisplay();
    const int postW = renderer_->targets().postWidth(), postH = renderer_->targets().postHeight();
    if (postW != request.width || postH != request.height) {   // no TAA upsampling: the spatial upscale
        result.hdr = catmullRomUpscale(result.hdr, postW, postH, request.width, request.height);
        result.display = catmullRomUpscale(result.display, postW, postH, request.width, request.height);
    }

    auto passList = [](const std::vector<PassTiming>& timings) {
        nlohmann::json list = nlohmann::json::array();
        for (const PassTiming& t : timings)
            list.push_back({{"name", t.name}, {"wall_ms", t.wallMs}, {"gpu_timer_ms", t.gpuMs}});
        return list;
    };
    nlohmann::json passes = passList(renderer_->passTimings());
    std::string rendererName = context_->rendererString();
    bool software = rendererName.find("llvmpipe") != std::string::npos || rendererName.find("softpipe") != std::string::npos;
    std::string aovName = "final";
    for (const AovInfo& aov : aovTable())
        if (aov.viewId == request.settings.debugView) aovName = aov.name;
    size_t nonFinite = 0;
    for (float v : result.hdr) nonFinite += !std::isfinite(v);
    result.stats = {
        {"resolution", {request.width, request.height}},
        {"render_resolution", {renderW, renderH}},
        {"upscale", renderer_->upsampled() ? "taa" : (postW != request.width || postH != request.height) ? "catmull-rom" : "none"},
        {"backend", backendName(context_->backend())},
        {"gl_renderer", rendererName},
        {"gl_version", context_->versionString()},
        {"gpu_timers_meaningful", !software},
        {"scene", scene_.name},
        {"camera", camera.name},
        {"method", request.settings.method},
        {"ibl", {{"mode", request.settings.ibl}, {"spp", samples}}},
        {"aov", aovName},
        {"image", {{"aa", request.settings.common_("aa") == 1 ? "taa" : "off"},
                   {"taa_frames", renderer_->taaFrames()},
                   {"tonemap", std::array<const char*, 3>{"aces", "neutral", "agx"}[size_t(
                                   request.settings.common_("tonemap"))]},
                   {"bloom_strength", request.settings.common_("bloom.strength")},
                   {"exposure_auto", request.settings.common_("exposure.auto") > 0.5f},
                   {"metered_ev", request.settings.common_("exposure.auto") > 0.5f
                                      ? renderer_->meteredExposureEv()
                                      : 0.0f}}},
        {"passes", passes},
        {"frame_ms", frameMs.back()},
        {"frames_ms", frameMs},
        {"frames_cpu_ms", frameCpuMs},
        {"first_frame_passes", passList(firstPasses)},
        {"frame_cpu_ms", frameCpuMs.back()},
        {"frames", frameMs.size()},
        {"frame_ms_each", frameMs},   // frame 0 includes on-demand work (e.g. the reflection probes' capture)
        {"scene_load_ms", sceneLoadMs_},
        {"program_build_ms", programBuildMs_},
        {"environment", renderer_->environment().stats()},
        {"probes", renderer_->probes().stats()},
        {"counts", {{"meshes", scene_.meshes.size()}, {"instances", scene_.instances.size()},
                    {"triangles", scene_.triangleCount()}, {"materials", scene_.materials.size()},
                    {"lights", scene_.lights.size()}, {"non_finite_values", nonFinite}}},
        // The last G-buffer pass after frustum culling of the meshes' chunks (back-face culling not counted).
        {"gbuffer_draw", {{"chunks", gpuScene_->lastDrawStats().chunksTotal},
                          {"chunks_drawn", gpuScene_->lastDrawStats().chunksDrawn},
                          {"triangles_drawn", gpuScene_->lastDrawStats().trianglesDrawn},
                          {"chunks_simplified", gpuScene_->lastDrawStats().chunksCoarser},
                          {"triangles_full_detail", gpuScene_->lastDrawStats().trianglesFullDetail}}},
        // The last frame's shadow passes: views in use, views re-rendered (0 when every map was cached), and the
        // triangles they drew after culling each view's chunks.
        {"shadows", {{"enabled", renderer_->shadowMaps().settings().enabled},
                     {"views", renderer_->shadowMaps().stats().views},
                     {"sun_views_rendered", renderer_->shadowMaps().stats().sunViewsRendered},
                     {"point_views_rendered", renderer_->shadowMaps().stats().localViewsRendered},
                     {"triangles_drawn", renderer_->shadowMaps().stats().trianglesDrawn}}},
    };
    return result;
}

RenderResult renderOffscreen(const RenderRequest& request) {
    OffscreenSession session(request);
    return session.render(request);
}

}  // namespace glimmer
