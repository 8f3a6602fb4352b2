// glimmer render: one offscreen frame to PNG (tone-mapped sRGB) or EXR (linear float).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/commands.h"
#include "app/common_options.h"
#include "app/render_path.h"
#include "bench/compare.h"
#include "core/cli.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "glints/user/user_methods.h"
#include "reference/discrete_facets/reference_render.h"
#include "render/aov.h"
#include "offscreen/offscreen.h"
#include "render/settings.h"

namespace glimmer {

static const char* kRenderHelp =
    "usage: glimmer render --scene NAME|PATH [--camera NAME] [--size WxH] [--backend egl|osmesa]\n"
    "                      [--method NAME] [--set KEY=VALUE ...] [--env PATH|none|procedural|constant:R,G,B]\n"
    "                      [--ibl MODE] [--spp N] [--aov NAME] [--frames N] [--render-scale F] [--shader-dir DIR]\n"
    "                      [--stats]\n"
    "                      [--allow-outside-uris] [--method-file PATH.glsl ...] --out FILE.png|FILE.exr\n"
    "       glimmer render --compare m1,m2,... [--crop x,y,w,h ...] [scene/size/--set options] --out FILE.png\n"
    "       glimmer render --path CAMERA_PATH.json [--frames N] [--fps F] [scene/size/method options]\n"
    "                      --out DIR/%04d.png [--video FILE.mp4|.gif|.webm]\n"
    "       glimmer render --list-params | --list-aovs | --list-scenes\n"
    "  --method defaults to deliot2023 (--method smooth: no glints). --method-file PATH.glsl loads a user method\n"
    "  (docs/user_methods.md; the first one is the method unless --method is given); anywhere a method is named,\n"
    "  file:PATH.glsl loads one too (--compare deliot2023,file:my_glints.glsl).\n"
    "  --path renders the camera path recorded in the window (R) at a fixed time step: frame i shows the path at\n"
    "  i/F s (default F 30), so N frames cover (N-1)/F s (default N: the whole path). The scene is the path file's\n"
    "  \"scene\" unless --scene is given. --video encodes the frames with the ffmpeg program (without ffmpeg the\n"
    "  --out frames are still written and the run fails at the end, saying so).\n"
    "  --render-scale F (0.25 .. 1) renders at F x the size and outputs the size: with --set aa=taa TAA resolves to\n"
    "  it (TAA upsampling, docs/image.md), otherwise a Catmull-Rom upscale (the window's).\n"
    "  PNG output is tone-mapped sRGB; EXR is linear radiance (or the raw AOV), 32-bit float.\n"
    "  --env: environment map (default: the scene's, else the procedural sky). --ibl: how it is integrated\n"
    "  (default prefiltered; Monte Carlo modes average --spp estimates; see --list-params).\n"
    "  --compare renders smooth and each listed method side by side, labelled; each --crop (render pixels, top-left\n"
    "  origin) adds a nearest-neighbour zoomed inset below every tile.\n";

int runRenderCommand(const std::vector<std::string>& argList) {
    ArgReader args("render", argList);
    if (args.flag("--help")) { std::fputs(kRenderHelp, stdout); return 0; }
    if (args.flag("--list-params")) {
        // With the user methods given, so their parameters are listed like the built-ins'.
        for (const std::string& file : args.values("--method-file")) loadUserMethodFile(file);
        std::fputs(describeParams().c_str(), stdout);
        return 0;
    }
    if (args.flag("--list-aovs")) {
        for (const AovInfo& aov : aovTable()) std::printf("  %-10s %s\n", aov.name.c_str(), aov.meaning.c_str());
        return 0;
    }
    if (args.flag("--list-scenes")) { std::fputs(describeScenes().c_str(), stdout); return 0; }

    // The discrete-facet reference is offered here only (--method reference, --compare ...,reference).
    facets::registerReferenceMethod();
    // A camera path belongs to its scene: without --scene, render it in the scene the path file names (rendering
    // the atrium's path over plane90 showed an empty plane).
    std::optional<std::string> pathFile = args.value("--path");
    std::string defaultScene = "plane90";
    // (Looked up in the raw list: ArgReader hands each value out once, and readCommonRenderOptions reads --scene.)
    bool sceneGiven = std::any_of(argList.begin(), argList.end(), [](const std::string& a) {
        return a == "--scene" || a.rfind("--scene=", 0) == 0;
    });
    if (pathFile && !sceneGiven) defaultScene = sceneOfPathFile(*pathFile);
    RenderRequest request = readCommonRenderOptions(args, defaultScene, "deliot2023");
    request.width = request.height = 512;
    if (auto size = args.value("--size")) parseSize(*size, "--size", request.width, request.height);
    if (pathFile) {
        PathRenderOptions path;
        path.pathFile = *pathFile;
        if (int frames = args.intValue("--frames", 0, 1, 1000000); frames > 0) path.frames = frames;
        if (auto fps = args.value("--fps")) {
            char* end = nullptr;
            path.fps = std::strtod(fps->c_str(), &end);
            if (fps->empty() || *end != '\0') throw UsageError("--fps: '" + *fps + "' is not a number");
        }
        path.outPattern = args.value("--out");
        path.video = args.value("--video");
        args.finish();
        checkPathRenderOptions(path);
        return renderPathSequence(request, path);
    }
    bool printStats = args.flag("--stats");
    request.frames = args.intValue("--frames", 1, 1, 100000);
    if (auto scale = args.value("--render-scale")) {
        char* end = nullptr;
        request.renderScale = std::strtof(scale->c_str(), &end);
        if (scale->empty() || *end != '\0' || !(request.renderScale >= 0.25f && request.renderScale <= 1.0f))
            throw UsageError("--render-scale: '" + *scale + "' is not a number in [0.25, 1]");
        if (request.settings.debugView != 0 && request.renderScale < 1.0f)
            throw UsageError("--render-scale: not with --aov (AOVs are not resampled; render them at the size wanted)");
    }
    auto out = args.value("--out");
    std::optional<std::string> compare = args.value("--compare");
    std::vector<bench::CropRect> crops;
    for (const std::string& text : args.values("--crop")) crops.push_back(bench::parseCrop(text));
    args.finish();
    if (!crops.empty() && !compare) throw UsageError("--crop: only with --compare");
    std::vector<std::string> compareMethods;
    if (compare) {
        std::stringstream list(*compare);
        for (std::string id; std::getline(list, id, ',');)
            if (!id.empty()) compareMethods.push_back(resolveGlintMethod(id, "--compare"));   // file:PATH too
        if (compareMethods.empty()) throw UsageError("--compare: expected a comma-separated list of methods");
        bench::comparisonMethods(compareMethods);  // unknown ids fail before any rendering
    }
    if (!out) throw UsageError("render: --out FILE.png|FILE.exr is required");
    std::filesystem::path outPath(*out);
    ImageFormat format = imageFormatForPath(outPath, "--out");
    // Fail on an unwritable destination before spending time on the render (the write itself is atomic); a
    // missing folder is created.
    createOutputFolder(outPath, "--out");
    checkOutputPath(outPath, "--out");

    if (compare) {
        if (format != ImageFormat::Png) throw UsageError("--compare: --out must be a .png file");
        bench::CustomTile reference{facets::kReferenceMethodId,
                                    [](OffscreenSession& session, const RenderRequest& r) { return facets::renderReference(session, r); },
                                    [](OffscreenSession& session, const RenderRequest& r) {
                                        return facets::referenceCaption(session.scene(), r.settings);
                                    }};
        bench::CompareGrid grid = bench::renderComparison(request, compareMethods, crops, {reference});
        std::vector<uint8_t> bottomUp(grid.rgba.size());
        size_t row = size_t(grid.width) * 4;
        for (int y = 0; y < grid.height; ++y)
            std::copy_n(&grid.rgba[size_t(grid.height - 1 - y) * row], row, &bottomUp[size_t(y) * row]);
        writePng(outPath, bottomUp.data(), grid.width, grid.height);
        std::printf("%s\n", outPath.string().c_str());
        return 0;
    }
    RenderResult result;
    if (request.settings.method == facets::kReferenceMethodId) {
        RenderRequest smooth = request;   // the session starts on smooth, whose AOVs the reference reads first
        smooth.settings.method = "smooth";
        OffscreenSession session(smooth);
        result = facets::renderReference(session, request);
    } else {
        result = renderOffscreen(request);
    }
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
