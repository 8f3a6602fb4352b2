#include "bench/bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <sstream>

#include "core/error.h"
#include "core/files.h"
#include "glints/methods.h"
#include "offscreen/offscreen.h"

namespace glimmer::bench {

const std::vector<BenchSuite>& benchSuites() {
    static const std::vector<BenchSuite> suites = {
        {"deliot2023-table1",
         "Deliot & Belcour 2023, Table 1: Beckmann alpha = 1.0, min and max over a sweep of microfacet density "
         "(material.density_scale multiplies every method's density).",
         {"sphere", "plane90", "plane25", "heightmap90", "heightmap25", "atrium"},
         {{"beckmann a=1.0", {"material.ndf=beckmann", "material.alpha=1.0"}}},
         "material.density_scale",
         {0.01, 0.1, 1.0, 10.0},
         0},
        // The paper does not state the two roughness values; 0.1 and 0.5 are ours.
        {"kemppinen2025-table3",
         "Kemppinen et al. 2025, Table 3: 90 and 25 degree planes, low (alpha 0.1) and high (alpha 0.5) roughness, "
         "Beckmann and GGX, 3 lights.",
         {"plane90", "plane25"},
         {{"beckmann low", {"material.ndf=beckmann", "material.alpha=0.1"}},
          {"ggx low", {"material.ndf=ggx", "material.alpha=0.1"}},
          {"beckmann high", {"material.ndf=beckmann", "material.alpha=0.5"}},
          {"ggx high", {"material.ndf=ggx", "material.alpha=0.5"}}},
         "",
         {},
         3},
        // Issue 37's budgets (docs/area_lights.md): at most 1.3x each. Kneiphof & Klein 2024: one rect light against
        // one directional light of about the same irradiance on plane90 (content/bench/).
        {"kk24-area-lights",
         "Kneiphof & Klein 2024: plane90 under its sun (a directional light) and under a rect light in its place "
         "(content/bench/sun_plane.json, rect_plane.json), every method.",
         {(defaultContentDir() / "bench" / "sun_plane.json").string(),
          (defaultContentDir() / "bench" / "rect_plane.json").string()},
         {{"", {}}},
         "",
         {},
         0},
        // Kneiphof & Klein 2025: the environment's glints off, with 4 and with 8 radiance levels (plane25: the sky
        // fills the reflected lobe; the atrium: the court and the arcades with their probes).
        {"kk25-environment",
         "Kneiphof & Klein 2025: environment glints off, 4 and 8 radiance levels (ibl.glint_levels), on plane25 "
         "and in the atrium.",
         {"plane25", "atrium"},
         {{"env glints off", {"ibl.glint_levels=off"}},
          {"4 levels", {"ibl.glint_levels=4"}},
          {"8 levels", {"ibl.glint_levels=8"}}},
         "",
         {},
         0},
        // Issue 13's budget: TAA + exposure + bloom at most 15% of the atrium frame (docs/image.md).
        {"image-pipeline",
         "The image pipeline's cost: the same frames without (aa off, no bloom, manual exposure) and with TAA, "
         "auto exposure and bloom 0.04; the per-pass times are in the JSON.",
         {"atrium"},
         {{"plain", {"aa=off", "bloom.strength=0", "exposure=0"}},
          {"taa+exposure+bloom", {"aa=taa", "bloom.strength=0.04", "exposure=auto"}}},
         "",
         {},
         0},
    };
    return suites;
}

const BenchSuite& findBenchSuite(const std::string& name) {
    std::string known;
    for (const BenchSuite& s : benchSuites()) {
        if (s.name == name) return s;
        known += (known.empty() ? "" : ", ") + s.name;
    }
    throw UsageError("--suite: unknown suite '" + name + "' (known: " + known + ")");
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

static std::string formatNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

std::vector<BenchCase> expandCases(const BenchOptions& options) {
    BenchSuite custom{"", "", {"plane90"}, {{"", {}}}, "", {}, 0};
    const BenchSuite& suite = options.suite.empty() ? custom : findBenchSuite(options.suite);
    std::vector<std::string> scenes = options.scenes.empty() ? suite.scenes : options.scenes;
    std::vector<std::string> methods;
    if (options.methods.empty()) {
        for (const GlintMethod& m : glintMethods()) methods.push_back(m.id);
    } else {
        for (const std::string& id : options.methods) methods.push_back(findGlintMethod(id).id);
    }
    // Every ratio is to smooth measured in the same run.
    if (std::find(methods.begin(), methods.end(), "smooth") == methods.end()) methods.insert(methods.begin(), "smooth");
    int lights = options.lights >= 0 ? options.lights : suite.lights;
    std::vector<double> sweep = suite.sweepValues;
    if (suite.sweepParam.empty()) sweep = {0.0};

    std::vector<BenchCase> cases;
    for (const std::string& scene : scenes)
        for (const BenchVariant& variant : suite.variants)
            for (const std::string& method : methods)
                for (double value : sweep) {
                    BenchCase c{scene, variant.label, method, suite.sweepParam, suite.sweepParam.empty() ? 0.0 : value,
                                variant.sets};
                    if (!suite.sweepParam.empty()) c.sets.push_back(suite.sweepParam + "=" + formatNumber(value));
                    if (lights > 0) c.sets.push_back("light.count=" + std::to_string(lights));
                    c.sets.insert(c.sets.end(), options.extraSets.begin(), options.extraSets.end());
                    cases.push_back(std::move(c));
                }
    return cases;
}

static std::string utcNow() {
    std::time_t now = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return text;
}

BenchReport runBench(const BenchOptions& options) {
    std::vector<BenchCase> cases = expandCases(options);
    BenchReport report;
    report.meta = {{"suite", options.suite.empty() ? "custom" : options.suite},
                   {"resolution", {options.width, options.height}},
                   {"frames", options.frames},
                   {"warmup", options.warmup},
                   {"ibl", options.ibl},
                   {"environment", options.environment ? *options.environment : std::string("scene default")},
                   {"date_utc", utcNow()},
                   {"timing", "wall clock per frame closed by glFinish; median, min, max over the timed frames"}};
    if (!options.suite.empty()) report.meta["description"] = findBenchSuite(options.suite).description;

    std::unique_ptr<OffscreenSession> session;
    std::string sessionScene;
    for (size_t i = 0; i < cases.size(); ++i) {
        const BenchCase& c = cases[i];
        RenderRequest request;
        request.scene = c.scene;
        request.camera = options.camera;
        request.width = options.width;
        request.height = options.height;
        request.backend = options.backend;
        request.shaderRoot = options.shaderRoot;
        request.environment = options.environment;
        request.settings.method = c.method;
        request.settings.ibl = options.ibl;
        for (const std::string& set : c.sets) request.settings.apply(set);
        if (!session || sessionScene != c.scene) {
            session.reset();  // one context at a time
            session = std::make_unique<OffscreenSession>(request);
            sessionScene = c.scene;
            // A fresh session's first frames run slower for longer than one warm-up frame on llvmpipe
            // (docs/measurements.md); settle before the first timed case.
            request.frames = 3;
            session->render(request);
        }
        if (options.warmup > 0) {  // program switch, first-use costs, caches
            request.frames = options.warmup;
            session->render(request);
        }
        BenchResult result{c, {}, 0, 0, 0, 0, 0, 0};
        request.frames = 1;
        for (int f = 0; f < options.frames; ++f) {
            RenderResult frame = session->render(request);
            result.samples.push_back({frame.stats["frame_ms"].get<double>(), frame.stats["frame_cpu_ms"].get<double>(),
                                      frame.stats["passes"]});
            if (report.meta.find("gl_renderer") == report.meta.end()) {
                report.meta["gl_renderer"] = frame.stats["gl_renderer"];
                report.meta["gl_version"] = frame.stats["gl_version"];
                report.meta["backend"] = frame.stats["backend"];
                report.meta["gpu_timers_meaningful"] = frame.stats["gpu_timers_meaningful"];
            }
        }
        std::vector<double> wall, cpu;
        for (const BenchSample& s : result.samples) {
            wall.push_back(s.wallMs);
            cpu.push_back(s.cpuMs);
        }
        result.medianMs = median(wall);
        result.minMs = *std::min_element(wall.begin(), wall.end());
        result.maxMs = *std::max_element(wall.begin(), wall.end());
        result.cpuMedianMs = median(cpu);
        if (options.progress) {
            char line[256];
            std::snprintf(line, sizeof line, "[%zu/%zu] %s %s %s%s%s: median %.2f ms (min %.2f, max %.2f)", i + 1,
                          cases.size(), c.scene.c_str(), c.variant.empty() ? "-" : c.variant.c_str(), c.method.c_str(),
                          c.sweepParam.empty() ? "" : (" " + c.sweepParam + "=").c_str(),
                          c.sweepParam.empty() ? "" : formatNumber(c.sweepValue).c_str(), result.medianMs,
                          result.minMs, result.maxMs);
            options.progress(line);
        }
        report.results.push_back(std::move(result));
    }
    session.reset();
    deriveFigures(report);
    return report;
}

// The result of `method` in `scene` at the variant and sweep point of `like`: the one it is compared with.
static const BenchResult* findResult(const BenchReport& report, const std::string& method, const std::string& scene,
                                     const BenchCase& like) {
    for (const BenchResult& r : report.results)
        if (r.benchCase.method == method && r.benchCase.scene == scene && r.benchCase.variant == like.variant &&
            r.benchCase.sweepValue == like.sweepValue)
            return &r;
    return nullptr;
}

static nlohmann::json geometricMean(const std::vector<double>& values) {
    if (values.empty()) return nullptr;
    double logSum = 0.0;
    for (double v : values) logSum += std::log(v);
    return std::exp(logSum / double(values.size()));
}

// The figures of every method for one timing metric (wall or CPU median).
static nlohmann::json figuresFor(const BenchReport& report, double BenchResult::*metric) {
    std::vector<std::string> methods;
    for (const BenchResult& r : report.results)
        if (std::find(methods.begin(), methods.end(), r.benchCase.method) == methods.end())
            methods.push_back(r.benchCase.method);
    nlohmann::json figures = nlohmann::json::object();
    for (const std::string& method : methods) {
        std::vector<double> overhead, anisotropy, speedup, toDeliot;
        std::map<std::string, std::pair<double, double>> sweepRange;  // scene|variant -> (min, max) of medians
        std::map<std::string, int> sweepCount;
        for (const BenchResult& r : report.results) {
            if (r.benchCase.method != method) continue;
            double value = r.*metric;
            if (const BenchResult* smooth = findResult(report, "smooth", r.benchCase.scene, r.benchCase);
                smooth && smooth->*metric > 0.0 && value > 0.0)
                overhead.push_back(value / smooth->*metric);
            std::string group = r.benchCase.scene + "|" + r.benchCase.variant;
            auto [it, inserted] = sweepRange.try_emplace(group, value, value);
            it->second.first = std::min(it->second.first, value);
            it->second.second = std::max(it->second.second, value);
            sweepCount[group]++;
            if (r.benchCase.scene == "plane25")
                if (const BenchResult* p90 = findResult(report, method, "plane90", r.benchCase);
                    p90 && p90->*metric > 0 && value > 0)
                    anisotropy.push_back(value / p90->*metric);
            if (const BenchResult* z = findResult(report, "zirr2016", r.benchCase.scene, r.benchCase);
                z && value > 0 && z->*metric > 0)
                speedup.push_back(z->*metric / value);
            if (const BenchResult* d = findResult(report, "deliot2023", r.benchCase.scene, r.benchCase);
                d && value > 0 && d->*metric > 0)
                toDeliot.push_back(value / d->*metric);
        }
        nlohmann::json stabilityPerGroup = nlohmann::json::object();
        double worst = 0.0;
        for (const auto& [group, range] : sweepRange) {
            if (sweepCount[group] < 2 || range.first <= 0.0) continue;
            double s = range.second / range.first;
            stabilityPerGroup[group] = s;
            worst = std::max(worst, s);
        }
        figures[method] = {
            {"overhead_vs_smooth", geometricMean(overhead)},
            {"stability_max_over_min", stabilityPerGroup.empty() ? nlohmann::json(nullptr) : nlohmann::json(worst)},
            {"stability_per_scene", stabilityPerGroup},
            {"anisotropy_plane25_over_plane90", geometricMean(anisotropy)},
            {"speedup_over_zirr2016", geometricMean(speedup)},
            {"ratio_to_deliot2023", geometricMean(toDeliot)},
        };
    }
    return figures;
}

void deriveFigures(BenchReport& report) {
    for (BenchResult& r : report.results) {
        const BenchResult* smooth = findResult(report, "smooth", r.benchCase.scene, r.benchCase);
        r.ratioToSmooth = smooth && smooth->medianMs > 0.0 ? r.medianMs / smooth->medianMs : 0.0;
        r.cpuRatioToSmooth = smooth && smooth->cpuMedianMs > 0.0 ? r.cpuMedianMs / smooth->cpuMedianMs : 0.0;
    }
    // Wall-clock figures at the top level; the same from process CPU time under "cpu" (steadier on a shared
    // machine with a software renderer).
    report.derived = figuresFor(report, &BenchResult::medianMs);
    nlohmann::json cpu = figuresFor(report, &BenchResult::cpuMedianMs);
    for (auto& [method, figures] : report.derived.items()) figures["cpu"] = cpu[method];
    report.derived["_definitions"] = {
        {"overhead_vs_smooth", "geometric mean over cases of median / smooth's median at the same point"},
        {"stability_max_over_min", "largest over scenes of max / min of the median over the density sweep"},
        {"anisotropy_plane25_over_plane90", "geometric mean of plane25 median / plane90 median at the same point"},
        {"speedup_over_zirr2016", "geometric mean of zirr2016's median / this method's median at the same point"},
        {"ratio_to_deliot2023", "geometric mean of this method's median / deliot2023's median at the same point"},
        {"cpu", "the same figures from the median process CPU time per frame (all threads) instead of wall time"},
    };
}

nlohmann::json toJson(const BenchReport& report) {
    nlohmann::json results = nlohmann::json::array();
    for (const BenchResult& r : report.results) {
        nlohmann::json samples = nlohmann::json::array();
        for (const BenchSample& s : r.samples)
            samples.push_back({{"wall_ms", s.wallMs}, {"cpu_ms", s.cpuMs}, {"passes", s.passes}});
        const BenchCase& c = r.benchCase;
        results.push_back({{"scene", c.scene},
                           {"variant", c.variant},
                           {"method", c.method},
                           {"sweep_param", c.sweepParam},
                           {"sweep_value", c.sweepValue},
                           {"sets", c.sets},
                           {"median_ms", r.medianMs},
                           {"min_ms", r.minMs},
                           {"max_ms", r.maxMs},
                           {"cpu_median_ms", r.cpuMedianMs},
                           {"cpu_ratio_to_smooth", r.cpuRatioToSmooth > 0.0 ? nlohmann::json(r.cpuRatioToSmooth) : nlohmann::json()},
                           {"ratio_to_smooth", r.ratioToSmooth > 0.0 ? nlohmann::json(r.ratioToSmooth) : nlohmann::json()},
                           {"samples", samples}});
    }
    nlohmann::json meta = report.meta;
    meta["gpu_timer_note"] = "passes[].gpu_timer_ms are GL_TIME_ELAPSED queries: meaningful only when "
                             "gpu_timers_meaningful is true (real GPUs); software renderers time the submit";
    return {{"schema", "glimmer-bench/1"}, {"meta", meta}, {"results", results}, {"derived", report.derived}};
}

static std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

std::string toCsv(const BenchReport& report) {
    std::ostringstream out;
    out << "scene,variant,method,sweep_param,sweep_value,sample,wall_ms,cpu_ms,median_ms,ratio_to_smooth,"
           "gbuffer_gpu_timer_ms,lighting_gpu_timer_ms,tonemap_gpu_timer_ms,gpu_timers_meaningful\n";
    // GL timer queries time the submit on software renderers: every row says whether its timer columns mean anything.
    std::string meaningful = report.meta.is_object() && report.meta.value("gpu_timers_meaningful", false) ? "1" : "0";
    for (const BenchResult& r : report.results) {
        const BenchCase& c = r.benchCase;
        for (size_t i = 0; i < r.samples.size(); ++i) {
            const BenchSample& s = r.samples[i];
            auto gpu = [&](const char* name) {
                for (const auto& p : s.passes)
                    if (p.value("name", "") == name) return formatNumber(p.value("gpu_timer_ms", 0.0));
                return std::string();
            };
            out << csvField(c.scene) << ',' << csvField(c.variant) << ',' << c.method << ',' << c.sweepParam << ','
                << formatNumber(c.sweepValue) << ',' << i << ',' << formatNumber(s.wallMs) << ','
                << formatNumber(s.cpuMs) << ',' << formatNumber(r.medianMs) << ','
                << (r.ratioToSmooth > 0 ? formatNumber(r.ratioToSmooth) : "") << ',' << gpu("gbuffer") << ','
                << gpu("lighting") << ',' << gpu("tonemap") << ',' << meaningful << '\n';
        }
    }
    return out.str();
}

static std::string fixed(double v, int digits) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", digits, v);
    return text;
}

static std::string figure(const nlohmann::json& v, const char* suffix) {
    return v.is_number() ? fixed(v.get<double>(), 2) + suffix : std::string("-");
}

std::string toMarkdown(const BenchReport& report) {
    std::vector<std::string> methods, columns;  // columns: scene | variant
    std::map<std::string, std::pair<std::string, std::string>> columnParts;
    for (const BenchResult& r : report.results) {
        const BenchCase& c = r.benchCase;
        if (std::find(methods.begin(), methods.end(), c.method) == methods.end()) methods.push_back(c.method);
        std::string column = c.scene + "|" + c.variant;
        if (std::find(columns.begin(), columns.end(), column) == columns.end()) {
            columns.push_back(column);
            columnParts[column] = {c.scene, c.variant};
        }
    }
    bool swept = !report.results.empty() && !report.results.front().benchCase.sweepParam.empty();
    std::ostringstream out;
    const nlohmann::json meta = report.meta.is_object() ? report.meta : nlohmann::json::object();
    std::string size = meta.contains("resolution") ? meta["resolution"][0].dump() + "x" + meta["resolution"][1].dump()
                                                   : std::string("?");
    out << "Suite `" << meta.value("suite", "custom") << "`, " << size << ", " << meta.value("frames", 0)
        << " timed frames after " << meta.value("warmup", 0) << " warm-up, renderer `" << meta.value("gl_renderer", "?")
        << "`. Median wall ms per frame (glFinish) and ratio to smooth in the same run"
        << (swept ? "; min-max over the density sweep" : "") << ". GL timer queries per pass are in the JSON and CSV"
        << (meta.value("gpu_timers_meaningful", false) ? "." : " but meaningless on this (software) renderer.")
        << "\n\n";
    auto timeTable = [&](double BenchResult::*metric, double BenchResult::*ratio) {
        out << "| method |";
        for (const std::string& col : columns) {
            const auto& [scene, variant] = columnParts[col];
            out << ' ' << scene << (variant.empty() ? "" : " " + variant) << " |";
        }
        out << "\n|---|";
        for (size_t i = 0; i < columns.size(); ++i) out << "---|";
        out << '\n';
        for (const std::string& method : methods) {
            out << "| " << method << " |";
            for (const std::string& col : columns) {
                double lo = 1e300, hi = 0, rlo = 1e300, rhi = 0;
                bool any = false;
                for (const BenchResult& r : report.results) {
                    if (r.benchCase.method != method || r.benchCase.scene + "|" + r.benchCase.variant != col) continue;
                    any = true;
                    lo = std::min(lo, r.*metric);
                    hi = std::max(hi, r.*metric);
                    rlo = std::min(rlo, r.*ratio);
                    rhi = std::max(rhi, r.*ratio);
                }
                if (!any) out << " - |";
                else if (swept)
                    out << ' ' << fixed(lo, 1) << "-" << fixed(hi, 1) << " (" << fixed(rlo, 2) << "-" << fixed(rhi, 2)
                        << "x) |";
                else
                    out << ' ' << fixed(lo, 1) << " (" << fixed(rlo, 2) << "x) |";
            }
            out << '\n';
        }
    };
    auto figureTable = [&](bool cpu) {
        out << "| method | overhead vs smooth | stability (max/min over sweep) | plane25 / plane90 | speed-up over "
               "zirr2016 | ratio to deliot2023 |\n|---|---|---|---|---|---|\n";
        for (const std::string& method : methods) {
            nlohmann::json d = report.derived.contains(method) ? report.derived[method] : nlohmann::json::object();
            if (cpu) d = d.contains("cpu") ? d["cpu"] : nlohmann::json::object();
            out << "| " << method << " | " << figure(d.value("overhead_vs_smooth", nlohmann::json()), "x") << " | "
                << figure(d.value("stability_max_over_min", nlohmann::json()), "") << " | "
                << figure(d.value("anisotropy_plane25_over_plane90", nlohmann::json()), "") << " | "
                << figure(d.value("speedup_over_zirr2016", nlohmann::json()), "x") << " | "
                << figure(d.value("ratio_to_deliot2023", nlohmann::json()), "x") << " |\n";
        }
    };
    timeTable(&BenchResult::medianMs, &BenchResult::ratioToSmooth);
    out << "\nDerived figures (wall clock):\n\n";
    figureTable(false);
    out << "\nProcess CPU time per frame (all threads; steadier than wall time when other work shares the machine), "
           "ms and ratio to smooth:\n\n";
    timeTable(&BenchResult::cpuMedianMs, &BenchResult::cpuRatioToSmooth);
    out << "\nDerived figures (CPU time):\n\n";
    figureTable(true);
    return out.str();
}

}  // namespace glimmer::bench
