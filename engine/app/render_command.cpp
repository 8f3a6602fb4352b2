// glimmer render: one offscreen frame to PNG (tone-mapped sRGB) or EXR (linear float).
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app/commands.h"
#include "app/common_options.h"
#include "core/cli.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "render/aov.h"
#include "render/offscreen.h"
#include "render/settings.h"

namespace glimmer {

static const char* kRenderHelp =
    "usage: glimmer render --scene NAME|PATH [--camera NAME] [--size WxH] [--backend egl|osmesa]\n"
    "                      [--method NAME] [--set KEY=VALUE ...] [--env PATH|none|procedural|constant:R,G,B]\n"
    "                      [--ibl MODE] [--spp N] [--aov NAME] [--frames N] [--shader-dir DIR] [--stats]\n"
    "                      --out FILE.png|FILE.exr\n"
    "       glimmer render --list-params | --list-aovs | --list-scenes\n"
    "  PNG output is tone-mapped sRGB; EXR is linear radiance (or the raw AOV), 32-bit float.\n"
    "  --env: environment map (default: the scene's, else the procedural sky). --ibl: how it is integrated\n"
    "  (default prefiltered; Monte Carlo modes average --spp estimates; see --list-params).\n";

int runRenderCommand(const std::vector<std::string>& argList) {
    ArgReader args("render", argList);
    if (args.flag("--help")) { std::fputs(kRenderHelp, stdout); return 0; }
    if (args.flag("--list-params")) { std::fputs(describeParams().c_str(), stdout); return 0; }
    if (args.flag("--list-aovs")) {
        for (const AovInfo& aov : aovTable()) std::printf("  %-10s %s\n", aov.name.c_str(), aov.meaning.c_str());
        return 0;
    }
    if (args.flag("--list-scenes")) { std::fputs(describeScenes().c_str(), stdout); return 0; }

    RenderRequest request = readCommonRenderOptions(args, "plane90");
    request.width = request.height = 512;
    if (auto size = args.value("--size")) parseSize(*size, "--size", request.width, request.height);
    bool printStats = args.flag("--stats");
    request.frames = args.intValue("--frames", 1, 1, 100000);
    auto out = args.value("--out");
    args.finish();
    if (!out) throw UsageError("render: --out FILE.png|FILE.exr is required");
    std::filesystem::path outPath(*out);
    ImageFormat format = imageFormatForPath(outPath, "--out");
    // Fail on an unwritable destination before spending time on the render.
    {
        std::error_code ec;
        std::filesystem::path parent = std::filesystem::absolute(outPath, ec).parent_path();
        if (!std::filesystem::is_directory(parent))
            throw Error("--out: " + outPath.string() + ": directory " + parent.string() + " does not exist");
        bool existed = std::filesystem::exists(outPath);
        std::ofstream probe(outPath, std::ios::app);
        if (!probe) throw Error("--out: " + outPath.string() + ": cannot write");
        probe.close();
        if (!existed) std::filesystem::remove(outPath, ec);  // a failed render must not leave an empty file
    }

    RenderResult result = renderOffscreen(request);
    if (format == ImageFormat::Exr) writeExr(outPath, result.hdr.data(), result.width, result.height);
    else writePng(outPath, result.display.data(), result.width, result.height);
    if (printStats) {
        result.stats["output"] = outPath.string();
        std::printf("%s\n", result.stats.dump().c_str());
    } else {
        std::printf("%s\n", outPath.string().c_str());
    }
    return 0;
}

}  // namespace glimmer
