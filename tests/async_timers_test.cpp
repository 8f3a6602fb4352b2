// The window's non-blocking GPU timers (Renderer::setAsyncGpuTimers): results arrive a few frames late, name
// every pass in order, and never come from the glFinish-measured path.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>

#include "core/clock.h"
#include "core/files.h"
#include "platform/context.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(AsyncGpuTimers, GlContext);
GLIMMER_SUITE_NEEDS(PassTimers, GlContext);

namespace glimmer {
namespace {

TEST(AsyncGpuTimers, ResultsArriveLateWithEveryPassNamedAndNoWallClock) {
    auto context = createHeadlessContext(Backend::Egl);
    Scene scene = loadScene("sphere");
    {
        GpuScene gpuScene(scene);
        Renderer renderer(defaultShaderDir(), RenderSettings{});
        renderer.setAsyncGpuTimers(true);
        const Camera& camera = scene.camera("");
        renderer.renderView(scene, gpuScene, camera, 64, 64);
        EXPECT_TRUE(renderer.passTimings().empty()) << "a frame's own queries cannot be read without waiting";
        std::vector<std::string> names;
        for (int frame = 0; frame < 12 && renderer.passTimings().empty(); ++frame) {
            glFinish();  // the test may wait so that results are surely available; the renderer must not
            renderer.renderView(scene, gpuScene, camera, 64, 64);
        }
        ASSERT_FALSE(renderer.passTimings().empty());
        for (const PassTiming& t : renderer.passTimings()) {
            names.push_back(t.name);
            EXPECT_EQ(t.wallMs, 0.0) << t.name;
            EXPECT_TRUE(std::isnan(t.gpuMs) || t.gpuMs >= 0.0) << t.name;   // NaN: no plausible result
        }
        ASSERT_GE(names.size(), 3u);
        EXPECT_EQ(names.front(), "shadow_sun");   // the sphere's sun, first frame: its cascades are drawn
        EXPECT_EQ(names.back(), "tonemap");

        // A new method: the frames in flight timed the previous passes, which the window must not list while the
        // new programs compile. The first readout after the change names the new method's own passes.
        RenderSettings wang;
        wang.method = "wang2020";
        renderer.setSettings(wang);
        EXPECT_TRUE(renderer.passTimings().empty()) << "the previous method's timings are gone";
        std::vector<std::string> after;
        for (int frame = 0; frame < 12 && after.empty(); ++frame) {
            glFinish();
            renderer.renderView(scene, gpuScene, camera, 64, 64);
            for (const PassTiming& t : renderer.passTimings()) after.push_back(t.name);
        }
        ASSERT_FALSE(after.empty());
        EXPECT_TRUE(std::any_of(after.begin(), after.end(), [](const std::string& n) { return n.rfind("glint_", 0) == 0; }))
            << "the first readout after the change is of a wang2020 frame (its glint passes)";

        // measurePasses still times with the wall clock, for this frame.
        renderer.renderView(scene, gpuScene, camera, 64, 64, true);
        ASSERT_FALSE(renderer.passTimings().empty());
        EXPECT_GT(renderer.passTimings().front().wallMs, 0.0);
    }
}

// Issue 19: the first pass of the first frame on a fresh (surfaceless EGL) context reported the machine's uptime
// as its GPU time (llvmpipe never executed the query's begin; render/frame/pass_timer.h). A GPU time can never
// exceed the wall time that contained the pass; a result that does is reported as none (NaN), in both modes.
TEST(PassTimers, GpuTimeNeverExceedsTheWallTimeAroundThePass) {
    auto context = createHeadlessContext(Backend::Egl);
    Scene scene = loadScene("plane90");
    {
        GpuScene gpuScene(scene);
        Renderer renderer(defaultShaderDir(), RenderSettings{});
        const Camera& camera = scene.camera("");
        renderer.renderView(scene, gpuScene, camera, 64, 36, true);   // the first frame of the context, measured
        // The frame's passes, after the sky-visibility bake or cache load of this new scene (wall time only).
        // On-demand work of a new scene (names with a dot: the sky-visibility bake or cache load, the reflection
        // probes' capture and prefilter) comes first, then the frame's passes (shadow_sun: plane90's sun).
        std::vector<std::string> names, onDemand;
        for (const PassTiming& t : renderer.passTimings())
            (t.name.find('.') != std::string::npos ? onDemand : names).push_back(t.name);
        EXPECT_EQ(std::count_if(onDemand.begin(), onDemand.end(),
                                [](const std::string& n) { return n == "ao.sky_bake" || n == "ao.sky_load"; }),
                  1);
        for (const std::string& n : onDemand)
            EXPECT_TRUE(n.rfind("ao.sky_", 0) == 0 || n.rfind("probes.", 0) == 0) << n;
        EXPECT_EQ(names, (std::vector<std::string>{"shadow_sun", "gbuffer", "gtao", "ao_resolve", "shadow_mask",
                                                   "lighting", "tonemap"}));
        for (const PassTiming& t : renderer.passTimings())
            EXPECT_TRUE(std::isnan(t.gpuMs) || t.gpuMs <= t.wallMs + 1.0)
                << t.name << ": " << t.gpuMs << " ms GPU inside " << t.wallMs << " ms wall";
    }
    {
        GpuScene gpuScene(scene);
        Renderer renderer(defaultShaderDir(), RenderSettings{});
        renderer.setAsyncGpuTimers(true);
        const Camera& camera = scene.camera("");
        Stopwatch clock;
        int readouts = 0;
        for (int frame = 0; frame < 8; ++frame) {
            glFinish();
            renderer.renderView(scene, gpuScene, camera, 64, 36);
            for (const PassTiming& t : renderer.passTimings()) {
                ++readouts;
                EXPECT_TRUE(std::isnan(t.gpuMs) || t.gpuMs <= clock.elapsedMs())
                    << t.name << ": " << t.gpuMs << " ms GPU in a " << clock.elapsedMs() << " ms test";
            }
        }
        EXPECT_GT(readouts, 0);
    }
}

}  // namespace
}  // namespace glimmer
