// The window's non-blocking GPU timers (Renderer::setAsyncGpuTimers): results arrive a few frames late, name
// every pass in order, and never come from the glFinish-measured path.
#include <gtest/gtest.h>

#include "core/files.h"
#include "platform/context.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"

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
        renderer.render(scene, gpuScene, camera, 64, 64);
        EXPECT_TRUE(renderer.passTimings().empty()) << "a frame's own queries cannot be read without waiting";
        std::vector<std::string> names;
        for (int frame = 0; frame < 12 && renderer.passTimings().empty(); ++frame) {
            glFinish();  // the test may wait so that results are surely available; the renderer must not
            renderer.render(scene, gpuScene, camera, 64, 64);
        }
        ASSERT_FALSE(renderer.passTimings().empty());
        for (const PassTiming& t : renderer.passTimings()) {
            names.push_back(t.name);
            EXPECT_EQ(t.wallMs, 0.0) << t.name;
            EXPECT_GE(t.gpuMs, 0.0) << t.name;
        }
        ASSERT_GE(names.size(), 3u);
        EXPECT_EQ(names.front(), "gbuffer");
        EXPECT_EQ(names.back(), "tonemap");

        // measurePasses still times with the wall clock, for this frame.
        renderer.render(scene, gpuScene, camera, 64, 64, true);
        ASSERT_FALSE(renderer.passTimings().empty());
        EXPECT_GT(renderer.passTimings().front().wallMs, 0.0);
    }
}

}  // namespace
}  // namespace glimmer
