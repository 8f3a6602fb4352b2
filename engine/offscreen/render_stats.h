// What `--stats` prints for an offscreen render (the JSON of RenderResult::stats): resolution and upscaling, the
// GL renderer, scene and method, per-pass times of the last and the first frame, wall and process-CPU frame times,
// counts, the G-buffer's and the shadow passes' draw statistics, the environment and the probes.
#pragma once
#include <nlohmann/json.hpp>

#include <vector>

#include "core/clock.h"
#include "platform/context.h"
#include "render/frame/pass_timer.h"
#include "render/renderer.h"

namespace glimmer {

struct RenderRequest;

// Wall clock and process CPU time (every thread, llvmpipe's rasterizer workers included: on a software renderer
// sharing the machine with other work it is far steadier than the wall clock) since construction.
class FrameClock {
public:
    FrameClock();
    double wallMs() const { return wall_.elapsedMs(); }
    double cpuMs() const;

private:
    Stopwatch wall_;
    double cpuStart_ = 0.0;
};

struct RenderTimings {
    std::vector<double> frameMs, frameCpuMs;
    std::vector<PassTiming> firstPasses;   // the first frame renders every shadow map; later ones reuse them
    void add(const FrameClock& clock) {
        frameMs.push_back(clock.wallMs());
        frameCpuMs.push_back(clock.cpuMs());
    }
};

struct RenderStatsInputs {
    const RenderRequest& request;
    const GLContext& context;
    const Scene& scene;
    const GpuScene& gpuScene;
    const Renderer& renderer;
    const RenderTimings& timings;
    const std::vector<float>& hdr;   // the result's radiance (non-finite values are counted)
    double sceneLoadMs = 0.0, programBuildMs = 0.0;
};
nlohmann::json renderStats(const RenderStatsInputs& in);

}  // namespace glimmer
