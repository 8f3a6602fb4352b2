// glimmer bench: the papers' performance tables (engine/bench/bench.h) and temporal flicker (bench/temporal.h).
// This file only reads flags and writes the outputs.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/commands.h"
#include "app/common_options.h"
#include "bench/bench.h"
#include "bench/temporal.h"
#include "core/cli.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "glints/user/user_methods.h"

namespace glimmer {

static const char* kBenchHelp =
    "usage: glimmer bench [--suite NAME] [--scenes a,b] [--methods a,b] [--size WxH] [--frames N] [--warmup N]\n"
    "                     [--lights K] [--camera NAME] [--set KEY=VALUE ...] [--env SPEC] [--ibl MODE]\n"
    "                     [--backend egl|osmesa] [--method-file PATH.glsl ...]\n"
    "                     [--json FILE] [--csv FILE] [--markdown FILE]\n"
    "       glimmer bench --temporal [--scenes a,b] [--methods a,b] [--size WxH] [--frames N] [--step S]\n"
    "                     [--aa off|taa] [--json FILE] [--markdown FILE]\n"
    "       glimmer bench --list-suites\n"
    "  Times each scene x method (x variant x density of the suite): warm-up frames, then N frames each closed by\n"
    "  glFinish (wall clock; median, min, max), ratio to smooth measured in the same run. Without --suite: one case\n"
    "  per --scenes (or --scene) and --methods (or --method; file:PATH.glsl names a user method). Smooth is\n"
    "  always timed. The Markdown table goes to stdout, progress to stderr. --temporal measures glint flicker\n"
    "  along a dolly of N cameras (step S x the distance to the target per frame, default 0.01); with --aa it\n"
    "  measures the displayed image rendered with that anti-aliasing instead of the glint AOV.\n";

static std::vector<std::string> splitList(const std::string& text, const char* flag) {
    std::vector<std::string> items;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) items.push_back(item);
    if (items.empty()) throw UsageError(std::string(flag) + ": empty list");
    return items;
}

static bool given(const std::vector<std::string>& args, const std::string& flag) {
    return std::any_of(args.begin(), args.end(),
                       [&](const std::string& a) { return a == flag || a.rfind(flag + "=", 0) == 0; });
}

// Fails before the (long) run when an output cannot be written.
static void checkWritable(const std::optional<std::string>& path, const char* flag) {
    if (path) checkOutputPath(*path, flag);
}

// Atomic (core/atomic_file.h): a failed write leaves no partial report and keeps an existing one.
static void writeText(const std::optional<std::string>& path, const char* flag, const std::string& text) {
    if (path) writeFileAtomically(*path, text, flag);
}

int runBenchCommand(const std::vector<std::string>& argList) {
    ArgReader args("bench", argList);
    if (args.flag("--help")) { std::fputs(kBenchHelp, stdout); return 0; }
    if (args.flag("--list-suites")) {
        for (const bench::BenchSuite& s : bench::benchSuites()) std::printf("  %-22s %s\n", s.name.c_str(), s.description.c_str());
        return 0;
    }
    bool sceneGiven = given(argList, "--scene"),
         methodGiven = given(argList, "--method") || given(argList, "--method-file");
    bool temporal = args.flag("--temporal");
    RenderRequest request = readCommonRenderOptions(args, "plane90");
    int width = temporal ? 640 : 1280, height = temporal ? 360 : 720;
    if (auto size = args.value("--size")) parseSize(*size, "--size", width, height);
    std::vector<std::string> scenes, methods;
    if (auto list = args.value("--scenes")) scenes = splitList(*list, "--scenes");
    else if (sceneGiven) scenes = {request.scene};
    if (auto list = args.value("--methods")) {
        for (const std::string& id : splitList(*list, "--methods")) methods.push_back(resolveGlintMethod(id, "--methods"));
    } else if (methodGiven) methods = {request.settings.method};
    // readCommonRenderOptions consumed (and validated) the --set flags; each case re-applies them to its own settings.
    std::vector<std::string> extraSets;
    for (size_t i = 0; i < argList.size(); ++i) {
        if (argList[i] == "--set" && i + 1 < argList.size()) extraSets.push_back(argList[++i]);
        else if (argList[i].rfind("--set=", 0) == 0) extraSets.push_back(argList[i].substr(6));
    }
    if (given(argList, "--aov") || given(argList, "--spp"))
        throw UsageError("bench: --aov and --spp are not supported (bench times the final image)");
    auto jsonPath = args.value("--json"), csvPath = args.value("--csv"), markdownPath = args.value("--markdown");
    checkWritable(jsonPath, "--json");
    checkWritable(csvPath, "--csv");
    checkWritable(markdownPath, "--markdown");
    auto progress = [](const std::string& line) { std::fprintf(stderr, "glimmer: %s\n", line.c_str()); };

    if (temporal) {
        bench::TemporalOptions options;
        options.scenes = scenes;
        options.methods = methods;
        options.camera = request.camera;
        options.width = width;
        options.height = height;
        options.frames = args.intValue("--frames", 8, 2, 1000);
        if (auto step = args.value("--step")) {
            char* end = nullptr;
            options.step = std::strtod(step->c_str(), &end);
            if (step->empty() || *end != '\0' || !(options.step >= 0.0 && options.step <= 1.0))
                throw UsageError("--step: '" + *step + "' is not a number in [0, 1]");
        }
        options.backend = request.backend;
        options.shaderRoot = request.shaderRoot;
        options.extraSets = extraSets;
        options.environment = request.environment;
        options.ibl = request.settings.ibl;
        options.progress = progress;
        if (auto aa = args.value("--aa")) {
            if (*aa != "off" && *aa != "taa") throw UsageError("--aa: '" + *aa + "' is not off or taa");
            options.aa = *aa;
        }
        if (csvPath) throw UsageError("--csv: not available with --temporal (use --json)");
        args.finish();
        std::vector<bench::TemporalResult> results = bench::runTemporal(options);
        std::string markdown = bench::temporalToMarkdown(results);
        std::fputs(markdown.c_str(), stdout);
        writeText(jsonPath, "--json", bench::temporalToJson(options, results).dump(2) + "\n");
        writeText(markdownPath, "--markdown", markdown);
        return 0;
    }

    bench::BenchOptions options;
    options.suite = args.valueOr("--suite", "");
    if (!options.suite.empty()) bench::findBenchSuite(options.suite);
    options.scenes = scenes;
    options.methods = methods;
    options.camera = request.camera;
    options.width = width;
    options.height = height;
    options.frames = args.intValue("--frames", 5, 1, 100000);
    options.warmup = args.intValue("--warmup", 1, 0, 1000);
    options.lights = args.intValue("--lights", -1, 0, 64);
    options.backend = request.backend;
    options.shaderRoot = request.shaderRoot;
    options.extraSets = extraSets;
    options.progress = progress;
    options.environment = request.environment;
    options.ibl = request.settings.ibl;
    args.finish();

    bench::BenchReport report = bench::runBench(options);
    std::string markdown = bench::toMarkdown(report);
    std::fputs(markdown.c_str(), stdout);
    writeText(jsonPath, "--json", bench::toJson(report).dump(2) + "\n");
    writeText(csvPath, "--csv", bench::toCsv(report));
    writeText(markdownPath, "--markdown", markdown);
    return 0;
}

}  // namespace glimmer
