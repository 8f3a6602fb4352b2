#include "offscreen/render_stats.h"

#include <array>
#include <cmath>
#include <ctime>

#include "offscreen/offscreen.h"
#include "render/aov.h"
#include "render/probes/reflection_probes.h"
#include "render/shadows/shadow_maps.h"

namespace glimmer {

namespace {

double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

nlohmann::json passList(const std::vector<PassTiming>& timings) {
    nlohmann::json list = nlohmann::json::array();
    for (const PassTiming& t : timings)
        list.push_back({{"name", t.name}, {"wall_ms", t.wallMs}, {"gpu_timer_ms", t.gpuMs}});
    return list;
}

}  // namespace

FrameClock::FrameClock() : cpuStart_(processCpuMs()) {}
double FrameClock::cpuMs() const { return processCpuMs() - cpuStart_; }

nlohmann::json renderStats(const RenderStatsInputs& in) {
    const RenderRequest& request = in.request;
    const Renderer& renderer = in.renderer;
    const RenderSettings& settings = request.settings;
    const View& view = renderer.lastView();
    const std::string rendererName = in.context.rendererString();
    const bool software = rendererName.find("llvmpipe") != std::string::npos || rendererName.find("softpipe") != std::string::npos;
    std::string aovName = "final";
    for (const AovInfo& aov : aovTable())
        if (aov.viewId == settings.debugView) aovName = aov.name;
    size_t nonFinite = 0;
    for (float v : in.hdr) nonFinite += !std::isfinite(v);
    const bool autoExposure = settings.value(param::exposure_auto) > 0.5f;
    const bool upscaled = view.postWidth != request.width || view.postHeight != request.height;
    const GpuScene::DrawStats& draws = in.gpuScene.lastDrawStats();
    const ShadowMaps& shadows = renderer.shadowMaps();
    const std::vector<double>& frameMs = in.timings.frameMs;
    const std::vector<double>& frameCpuMs = in.timings.frameCpuMs;
    return {
        {"resolution", {request.width, request.height}},
        {"render_resolution", {view.width, view.height}},
        {"upscale", renderer.upsampled() ? "taa" : upscaled ? "catmull-rom" : "none"},
        {"backend", backendName(in.context.backend())},
        {"gl_renderer", rendererName},
        {"gl_version", in.context.versionString()},
        {"gpu_timers_meaningful", !software},
        {"scene", in.scene.name},
        {"camera", view.camera.name},
        {"method", settings.method},
        {"ibl", {{"mode", settings.ibl}, {"spp", renderer.accumulating() ? std::max(request.spp, 1) : 1}}},
        {"aov", aovName},
        {"image", {{"aa", settings.value(param::aa) == 1 ? "taa" : "off"},
                   {"taa_frames", renderer.taaFrames()},
                   {"tonemap", std::array<const char*, 3>{"aces", "neutral", "agx"}[size_t(settings.value(param::tonemap))]},
                   {"bloom_strength", settings.value(param::bloom_strength)},
                   {"exposure_auto", autoExposure},
                   {"metered_ev", autoExposure ? renderer.meteredExposureEv() : 0.0f}}},
        {"passes", passList(renderer.passTimings())},
        {"frame_ms", frameMs.back()},
        {"frames_ms", frameMs},
        {"frames_cpu_ms", frameCpuMs},
        {"first_frame_passes", passList(in.timings.firstPasses)},
        {"frame_cpu_ms", frameCpuMs.back()},
        {"frames", frameMs.size()},
        {"frame_ms_each", frameMs},   // frame 0 includes on-demand work (e.g. the reflection probes' capture)
        {"scene_load_ms", in.sceneLoadMs},
        {"program_build_ms", in.programBuildMs},
        {"environment", renderer.environment().stats()},
        {"probes", renderer.probes().stats()},
        {"counts", {{"meshes", in.scene.meshes.size()}, {"instances", in.scene.instances.size()},
                    {"triangles", in.scene.triangleCount()}, {"materials", in.scene.materials.size()},
                    {"lights", in.scene.lights.size()}, {"non_finite_values", nonFinite}}},
        // The last G-buffer pass after frustum culling of the meshes' chunks (back-face culling not counted).
        {"gbuffer_draw", {{"chunks", draws.chunksTotal},
                          {"chunks_drawn", draws.chunksDrawn},
                          {"triangles_drawn", draws.trianglesDrawn},
                          {"chunks_simplified", draws.chunksCoarser},
                          {"triangles_full_detail", draws.trianglesFullDetail}}},
        // The last frame's shadow passes: views in use, views re-rendered (0 when every map was cached), and the
        // triangles they drew after culling each view's chunks.
        {"shadows", {{"enabled", shadows.settings().enabled},
                     {"views", shadows.stats().views},
                     {"sun_views_rendered", shadows.stats().sunViewsRendered},
                     {"point_views_rendered", shadows.stats().localViewsRendered},
                     {"triangles_drawn", shadows.stats().trianglesDrawn}}},
    };
}

}  // namespace glimmer
