// glimmer view: the walkthrough window. Renders with the same Renderer as `glimmer render` and presents the
// display image; `--frames N --screenshot FILE` renders N frames and exits (tests run it under xvfb-run).
#include <GLFW/glfw3.h>

#include <cstdio>

#include "app/commands.h"
#include "app/common_options.h"
#include "core/cli.h"
#include "core/error.h"
#include "core/files.h"
#include "core/image_io.h"
#include "platform/glfw_window.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"

namespace glimmer {

static const char* kViewHelp =
    "usage: glimmer view [--scene NAME|PATH] [--camera NAME] [--size WxH] [--method NAME] [--set KEY=VALUE ...]\n"
    "                    [--aov NAME] [--shader-dir DIR] [--frames N --screenshot FILE.png]\n";

int runViewCommand(const std::vector<std::string>& argList) {
    ArgReader args("view", argList);
    if (args.flag("--help")) { std::fputs(kViewHelp, stdout); return 0; }
    RenderRequest request = readCommonRenderOptions(args, "sphere");
    args.value("--backend");  // accepted for symmetry; the window always uses GLFW
    request.width = 1280;
    request.height = 720;
    if (auto size = args.value("--size")) parseSize(*size, "--size", request.width, request.height);
    int frameLimit = args.intValue("--frames", 0, 0, 1 << 30);
    auto screenshot = args.value("--screenshot");
    args.finish();
    if (screenshot) imageFormatForPath(*screenshot, "--screenshot");

    Scene scene = loadScene(request.scene);
    applySceneOverrides(request.settings, scene);
    Camera camera = scene.camera(request.camera);
    GlfwWindow window(request.width, request.height, "Glimmer - " + scene.name, frameLimit == 0);
    GpuScene gpuScene(scene);
    Renderer renderer(request.shaderRoot.empty() ? defaultShaderDir() : request.shaderRoot, request.settings);

    for (int frame = 0; !window.shouldClose() && (frameLimit == 0 || frame < frameLimit); ++frame) {
        glfwPollEvents();
        if (glfwGetKey(window.glfwHandle(), GLFW_KEY_ESCAPE) == GLFW_PRESS) window.requestClose();
        int width = 0, height = 0;
        window.framebufferSize(width, height);
        if (width <= 0 || height <= 0) continue;
        renderer.render(scene, gpuScene, camera, width, height);
        glBlitNamedFramebuffer(renderer.targets().displayFramebuffer(), 0, 0, 0, width, height, 0, 0, width, height,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
        if (screenshot && frameLimit != 0 && frame + 1 == frameLimit) {
            std::vector<uint8_t> pixels = renderer.readDisplay();
            writePng(*screenshot, pixels.data(), renderer.targets().width(), renderer.targets().height());
            std::printf("%s\n", screenshot->c_str());
        }
        window.swapBuffers();
    }
    return 0;
}

}  // namespace glimmer
