// `glimmer bench`: timing suites that mirror the glint papers' performance tables, run side by side in one process
// so that ratios to the smooth (no-glint) reference are measured under the same load. The command in
// engine/app/bench_command.cpp only parses flags; tests call runBench() in-process.
#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "platform/context.h"

namespace glimmer::bench {

// A named group of --set overrides applied to every method, e.g. "beckmann a=1.0".
struct BenchVariant {
    std::string label;
    std::vector<std::string> sets;
};

struct BenchSuite {
    std::string name;
    std::string description;                 // what it reproduces, printed by --list-suites and in the Markdown
    std::vector<std::string> scenes;
    std::vector<BenchVariant> variants;      // at least one
    std::string sweepParam;                  // common parameter swept per variant ("" = none)
    std::vector<double> sweepValues;
    int lights = 0;                          // light.count; 0 keeps the scene's lights
};

// Built-in suites: deliot2023-table1, kemppinen2025-table3, kk24-area-lights, kk25-environment, image-pipeline.
const std::vector<BenchSuite>& benchSuites();
// Throws UsageError naming --suite.
const BenchSuite& findBenchSuite(const std::string& name);

struct BenchOptions {
    std::string suite;                       // "" = one custom case per scene x method, no sweep
    std::vector<std::string> scenes;         // empty = the suite's (custom: plane90)
    std::vector<std::string> methods;        // empty = every method of the method table; smooth is always added
    std::string camera;
    int width = 1280, height = 720;
    int frames = 5, warmup = 1;
    int lights = -1;                         // -1 = the suite's; 0 = the scene's
    Backend backend = Backend::Egl;
    std::filesystem::path shaderRoot;
    std::vector<std::string> extraSets;      // --set given on the command line, applied after the variant's
    std::optional<std::string> environment;  // --env (default: the scene's)
    std::string ibl = "prefiltered";         // --ibl mode
    std::function<void(const std::string&)> progress;  // one line per case (the command prints to stderr)
};

struct BenchCase {
    std::string scene, variant, method;
    std::string sweepParam;                  // "" when the suite has no sweep
    double sweepValue = 0.0;
    std::vector<std::string> sets;           // every --set applied (variant, sweep, lights, extra)
};

struct BenchSample {
    double wallMs = 0.0;                     // wall clock of one frame closed by glFinish
    double cpuMs = 0.0;                      // process CPU time of that frame (all threads)
    nlohmann::json passes;                   // [{name, wall_ms, gpu_timer_ms}]
};

struct BenchResult {
    BenchCase benchCase;
    std::vector<BenchSample> samples;
    double medianMs = 0.0, minMs = 0.0, maxMs = 0.0, cpuMedianMs = 0.0;
    double ratioToSmooth = 0.0;              // median / smooth's median in the same scene, variant and sweep point
    double cpuRatioToSmooth = 0.0;           // the same from the CPU-time medians
};

struct BenchReport {
    nlohmann::json meta;                     // suite, size, frames, GL renderer/version, timer meaningfulness
    std::vector<BenchResult> results;
    nlohmann::json derived;                  // per method: overhead, stability, anisotropy, speed-up over zirr2016
};

// The cases a run would time, in run order (grouped by scene so one session serves each scene).
std::vector<BenchCase> expandCases(const BenchOptions& options);
BenchReport runBench(const BenchOptions& options);

// Fills ratioToSmooth and BenchReport::derived from the medians (runBench calls it; tests may call it on
// synthetic reports).
void deriveFigures(BenchReport& report);

nlohmann::json toJson(const BenchReport& report);
std::string toCsv(const BenchReport& report);       // one row per sample
std::string toMarkdown(const BenchReport& report);  // the papers' layout plus the derived figures

double median(std::vector<double> values);

}  // namespace glimmer::bench
