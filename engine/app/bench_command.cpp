// glimmer bench: frame timing of methods and scenes (wall clock around glFinish, median of N frames).
#include <algorithm>
#include <cstdio>

#include "app/commands.h"
#include "app/common_options.h"
#include "core/cli.h"
#include "core/error.h"
#include "render/offscreen.h"

namespace glimmer {

int runBenchCommand(const std::vector<std::string>& argList) {
    ArgReader args("bench", argList);
    RenderRequest request = readCommonRenderOptions(args, "plane90");
    request.width = 1280;
    request.height = 720;
    if (auto size = args.value("--size")) parseSize(*size, "--size", request.width, request.height);
    int frames = args.intValue("--frames", 10, 1, 100000);
    args.finish();
    OffscreenSession session(request);
    request.frames = 2;
    session.render(request);  // warm-up: compilation and first-use costs
    std::vector<double> samples;
    for (int i = 0; i < frames; ++i) {
        request.frames = 1;
        samples.push_back(session.render(request).stats["frame_ms"].get<double>());
        std::fprintf(stderr, "\rglimmer: bench frame %d/%d", i + 1, frames);
    }
    std::fprintf(stderr, "\n");
    std::sort(samples.begin(), samples.end());
    std::printf("%s %s %dx%d: median %.3f ms, min %.3f ms, max %.3f ms\n", request.scene.c_str(),
                request.settings.method.c_str(), request.width, request.height, samples[samples.size() / 2],
                samples.front(), samples.back());
    return 0;
}

}  // namespace glimmer
