#include "checks/method_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>

#include "core/error.h"
#include "reference/method_probe.h"
#include "glints/methods.h"
#include "render/aov.h"
#include "offscreen/offscreen.h"

namespace glimmer::checks {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Limits of the rules (docs/user_methods.md#check-method says why).
constexpr double kConvergenceMeanTolerance = 0.02;    // image mean within 2% of smooth
constexpr double kConvergencePixelTolerance = 0.05;   // 5x5-box-filtered pixels within 5% ...
constexpr double kConvergencePixelFraction = 0.01;    // ... on all but 1% of the pixels
constexpr double kFurnaceTolerance = 0.05;            // area-averaged energy within 5% of 1 ...
constexpr double kFurnaceMaxStdError = 0.02;          // ... measured to a standard error of 2% or better
constexpr double kConstantTimeBand = 1.3;             // plane25 / plane90 cost within x/÷ 1.3 of smooth's

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
    char text[256];
    std::snprintf(text, sizeof text, pattern, a, b, c, d);
    return text;
}

std::vector<double> pixelMeans(const std::vector<float>& rgba, int width, int height) {
    std::vector<double> v(size_t(width) * size_t(height));
    for (size_t i = 0; i < v.size(); ++i) v[i] = (double(rgba[4 * i]) + rgba[4 * i + 1] + rgba[4 * i + 2]) / 3.0;
    return v;
}

std::vector<double> boxFilter(const std::vector<double>& img, int w, int h, int radius) {
    std::vector<double> out(img.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0.0;
            int n = 0;
            for (int dy = -radius; dy <= radius; ++dy)
                for (int dx = -radius; dx <= radius; ++dx) {
                    int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
                    sum += img[size_t(yy) * size_t(w) + size_t(xx)];
                    ++n;
                }
            out[size_t(y) * size_t(w) + size_t(x)] = sum / n;
        }
    return out;
}

double mean(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / double(v.size());
}

// A half vector drawn from D_smooth(h) (n.h) for GGX (tan^2 = a^2 x / (1 - x)) or Beckmann (tan^2 = -a^2 ln(1 - x)).
glm::vec3 sampleHalfVector(int ndf, double alpha, double u1, double u2) {
    double tan2 = ndf == 0 ? alpha * alpha * u1 / std::max(1.0 - u1, 1e-12) : -alpha * alpha * std::log(std::max(1.0 - u1, 1e-12));
    double cosTheta = 1.0 / std::sqrt(1.0 + tan2), sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    double phi = 2.0 * kPi * u2;
    return glm::vec3(float(sinTheta * std::cos(phi)), float(sinTheta * std::sin(phi)), float(cosTheta));
}

ParamValues withConvergence(const GlintMethod& method) {
    ParamValues values = method.convergence;
    return values;
}

RenderRequest planeRequest(const std::string& scene, const CheckOptions& options, int size) {
    RenderRequest request;
    request.scene = scene;
    request.environment = "none";   // glints respond to the lights; the environment only adds a smooth term
    request.width = request.height = size;
    request.backend = options.backend;
    request.shaderRoot = options.shaderRoot;
    return request;
}

RuleResult convergenceRule(const GlintMethod& method, const CheckOptions& options) {
    RuleResult r{"convergence", "pass", "", ""};
    r.limit = format("mean within %.0f%%, 5x5-filtered pixels within %.0f%% on >= %.0f%% of pixels", 100 * kConvergenceMeanTolerance,
                     100 * kConvergencePixelTolerance, 100 * (1 - kConvergencePixelFraction));
    if (method.convergence.empty()) {
        r.status = "FAIL";
        r.measured = "the method declares no convergence values (header key 'converge: NAME=VALUE')";
        return r;
    }
    double worstMean = 0.0, worstFraction = 0.0;
    std::string worstCase;
    for (const char* scene : {"plane90", "plane25"}) {
        RenderRequest request = planeRequest(scene, options, options.size);
        request.settings.method = "smooth";
        OffscreenSession session(request);
        for (int ndf : {0, 1}) {
            RenderRequest smooth = request, glinty = request;
            smooth.settings.common["material.ndf"] = float(ndf);
            glinty.settings = smooth.settings;
            glinty.settings.method = method.id;
            glinty.settings.methods[method.id] = withConvergence(method);
            std::vector<float> a = session.render(glinty).hdr, b = session.render(smooth).hdr;
            SmoothGap gap = gapToSmooth(a, b, options.size, options.size, 2, kConvergencePixelTolerance);
            std::string label = std::string(scene) + (ndf ? " beckmann" : " ggx");
            if (options.progress)
                options.progress("convergence " + label + format(": mean ratio %.4f, %.2f%% of pixels beyond 5%%", gap.meanRatio,
                                                                  100 * gap.fractionAbove));
            double meanGap = std::abs(gap.meanRatio - 1.0);
            if (!std::isfinite(gap.meanRatio)) meanGap = 1e30;
            if (meanGap > kConvergenceMeanTolerance || gap.fractionAbove > kConvergencePixelFraction) r.status = "FAIL";
            if (meanGap >= worstMean) { worstMean = meanGap; worstCase = label; }
            worstFraction = std::max(worstFraction, gap.fractionAbove);
        }
    }
    std::string values;
    for (const auto& [k, v] : method.convergence) values += (values.empty() ? "" : ",") + k + "=" + format("%g", v);
    r.measured = "at " + values + ": worst mean gap " + format("%.2f%%", 100 * worstMean) + " (" + worstCase + "), " +
                 format("worst %.2f%% of pixels beyond 5%%", 100 * worstFraction) + " (plane90, plane25; GGX, Beckmann)";
    return r;
}

RuleResult furnaceRule(const GlintMethod& method, const ParamValues& values, const CheckOptions& options) {
    RuleResult r{"furnace", "pass", "", ""};
    r.limit = format("area mean of int D cos within %.0f%% of 1, std. error <= %.0f%%", 100 * kFurnaceTolerance,
                     100 * kFurnaceMaxStdError);
    double lowest = 1e30, highest = -1e30, worstError = 0.0;
    size_t nonFinite = 0;
    for (int ndf : {0, 1})
        for (float alpha : {0.2f, 0.5f})
            for (float footprint : {3e-3f, 1e-2f}) {
                // Sparse glints make the per-position integrals noisy: more positions until the standard error
                // is small enough to judge (at most 8x).
                FurnaceResult f;
                for (int points = 2048; points <= 16384; points *= 2) {
                    f = furnace(method.id, values, {ndf, alpha, footprint}, points, 64, options.shaderRoot);
                    if (f.stdError <= kFurnaceMaxStdError) break;
                }
                if (options.progress)
                    options.progress(std::string("furnace ") + (ndf ? "beckmann" : "ggx") +
                                     format(" alpha %.1f footprint %g: %.4f (std. error %.4f)", alpha, footprint, f.ratio,
                                            f.stdError));
                bool ok = std::abs(f.ratio - 1.0) <= kFurnaceTolerance && f.stdError <= kFurnaceMaxStdError;
                if (!ok || !std::isfinite(f.ratio)) r.status = "FAIL";
                lowest = std::min(lowest, f.ratio);
                highest = std::max(highest, f.ratio);
                worstError = std::max(worstError, f.stdError);
                nonFinite += f.nonFinite;
            }
    r.measured = format("energy / smooth %.3f .. %.3f (std. error <= %.3f) over GGX, Beckmann, alpha 0.2, 0.5, footprint 3e-3, 1e-2",
                        lowest, highest, worstError);
    if (nonFinite) r.measured += "; " + std::to_string(nonFinite) + " non-finite values left out";
    return r;
}

RuleResult finiteRule(const GlintMethod& method, const ParamValues& values, const CheckOptions& options) {
    RuleResult r{"finite", "pass", "", "no NaN, Inf or negative D, no non-finite AOV"};
    FiniteResult f = finiteSweep(method.id, values, options.shaderRoot);
    r.measured = std::to_string(f.evaluated) + " evaluations: " + std::to_string(f.nonFinite) + " non-finite, " +
                 std::to_string(f.negative) + " negative";
    if (f.nonFinite || f.negative) {
        r.status = "FAIL";
        r.measured += "; first: " + f.firstBad;
    }
    return r;
}

// Lighting-pass wall time (glFinish-closed) per frame, smooth and the method interleaved frame by frame so that
// both see the same machine load; the minimum over the frames.
struct SceneTiming {
    double smoothMs = 0.0, methodMs = 0.0;
};
SceneTiming timeScene(const std::string& scene, const GlintMethod& method, const ParamValues& values,
                      const CheckOptions& options) {
    RenderRequest smooth = planeRequest(scene, options, options.timingSize);
    smooth.settings.method = "smooth";
    RenderRequest glinty = smooth;
    glinty.settings.method = method.id;
    glinty.settings.methods[method.id] = values;
    OffscreenSession session(smooth);
    auto lightingMs = [&](const RenderRequest& request) {
        RenderResult result = session.render(request);
        for (const auto& pass : result.stats["passes"])
            if (pass["name"] == "lighting") return pass["wall_ms"].get<double>();
        return result.stats["frame_ms"].get<double>();
    };
    lightingMs(smooth);   // warm-up: program builds, method resources
    lightingMs(glinty);
    std::vector<double> a, b;
    for (int i = 0; i < options.timingFrames; ++i) {
        a.push_back(lightingMs(smooth));
        b.push_back(lightingMs(glinty));
    }
    // The fastest frame of each: load on a shared machine only ever adds time.
    return {*std::min_element(a.begin(), a.end()), *std::min_element(b.begin(), b.end())};
}

}  // namespace

SmoothGap gapToSmooth(const std::vector<float>& glinty, const std::vector<float>& smooth, int width, int height,
                      int boxRadius, double tolerance) {
    if (glinty.size() != smooth.size() || glinty.size() < size_t(width) * size_t(height) * 4)
        throw Error("internal: gapToSmooth needs two RGBA images of the same size");
    std::vector<double> a = pixelMeans(glinty, width, height), b = pixelMeans(smooth, width, height);
    SmoothGap gap;
    double meanB = mean(b);
    gap.meanRatio = mean(a) / meanB;
    std::vector<double> fa = boxFilter(a, width, height, boxRadius), fb = boxFilter(b, width, height, boxRadius);
    size_t above = 0;
    for (size_t i = 0; i < fa.size(); ++i) {
        double err = std::abs(fa[i] - fb[i]) / std::max(fb[i], 0.02 * meanB);
        if (!std::isfinite(err)) err = 1e30;
        gap.worstPixelError = std::max(gap.worstPixelError, err);
        above += err > tolerance;
    }
    gap.fractionAbove = double(above) / double(fa.size());
    return gap;
}

FurnaceResult furnace(const std::string& methodId, const ParamValues& values, const FurnaceCase& c, int points,
                      int halfVectorsPerPoint, const std::filesystem::path& shaderRoot) {
    GlintMethodProbe probe(methodId, values, shaderRoot);
    std::mt19937_64 rng(20231215);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    int side = std::max(1, int(std::lround(std::sqrt(double(halfVectorsPerPoint)))));
    int perPoint = side * side;
    std::vector<GlintProbeInput> inputs;
    inputs.reserve(size_t(points) * size_t(perPoint));
    const double patch = 64.0 * c.footprint;   // 64 x 64 footprints: many grid cells and glints per patch
    for (int p = 0; p < points; ++p) {
        glm::vec2 uv(float(64.0 + patch * u01(rng)), float(64.0 + patch * u01(rng)));
        for (int k = 0; k < perPoint; ++k) {
            // Stratified (jittered side x side) over the two sampling dimensions.
            double s1 = (double(k % side) + u01(rng)) / side, s2 = (double(k / side) + u01(rng)) / side;
            GlintProbeInput in;
            in.uv = uv;
            in.duvdx = {c.footprint, 0.0f};
            in.duvdy = {0.0f, 0.5f * c.footprint};
            in.h = sampleHalfVector(c.ndf, c.alpha, s1, s2);
            in.alpha = c.alpha;
            in.ndf = c.ndf;
            inputs.push_back(in);
        }
    }
    std::vector<GlintProbeOutput> out = probe.run(inputs);
    FurnaceResult result;
    std::vector<double> pointMeans;
    pointMeans.reserve(size_t(points));
    for (int p = 0; p < points; ++p) {
        double sum = 0.0;
        int n = 0;
        for (int k = 0; k < perPoint; ++k) {
            const GlintProbeOutput& o = out[size_t(p) * size_t(perPoint) + size_t(k)];
            if (!std::isfinite(o.D)) { ++result.nonFinite; continue; }
            if (o.smoothD > 0.0f) sum += double(o.D) / double(o.smoothD);
            ++n;
        }
        if (n) pointMeans.push_back(sum / n);
        result.samples += size_t(n);
    }
    double m = mean(pointMeans), var = 0.0;
    for (double v : pointMeans) var += (v - m) * (v - m);
    var /= std::max<double>(1.0, double(pointMeans.size()) - 1.0);
    result.ratio = m;
    result.stdError = std::sqrt(var / std::max<double>(1.0, double(pointMeans.size())));
    return result;
}

FiniteResult finiteSweep(const std::string& methodId, const ParamValues& values, const std::filesystem::path& shaderRoot) {
    GlintMethodProbe probe(methodId, values, shaderRoot);
    std::vector<GlintProbeInput> inputs;
    const float scales[] = {0.0f, 1e-9f, 1e-6f, 1e-3f, 0.1f, 10.0f, 1e4f};
    const float anisotropies[] = {1.0f, 16.0f, 1e4f};
    const float rotations[] = {0.0f, 0.7f};
    const float thetas[] = {0.0f, 30.0f, 60.0f, 85.0f, 89.9f, 90.0f};
    const float phis[] = {0.0f, 1.0f, 2.5f};
    const float alphas[] = {0.001f, 0.3f, 1.0f};
    const float densities[] = {0.0f, 1.0f, 1e6f};
    const glm::vec2 uvs[] = {{0.0f, 0.0f}, {1e4f, -1e4f}, {-37.3f, 12.9f}};
    for (float scale : scales)
        for (float aniso : anisotropies)
            for (float rot : rotations)
                for (float theta : thetas)
                    for (float phi : phis)
                        for (float alpha : alphas)
                            for (int ndf : {0, 1})
                                for (float density : densities)
                                    for (const glm::vec2& uv : uvs) {
                                        GlintProbeInput in;
                                        glm::vec2 major(std::cos(rot), std::sin(rot)), minor(-major.y, major.x);
                                        in.duvdx = major * scale;
                                        // Degenerate (collinear) derivatives at rotation 0.7 with anisotropy 16.
                                        in.duvdy = (aniso == 16.0f && rot > 0.0f) ? major * (scale / aniso) : minor * (scale / aniso);
                                        float t = glm::radians(theta), p = phi;
                                        in.h = {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
                                        in.alpha = alpha;
                                        in.ndf = ndf;
                                        in.densityScale = density;
                                        in.uv = uv;
                                        inputs.push_back(in);
                                    }
    std::vector<GlintProbeOutput> out = probe.run(inputs);
    FiniteResult result;
    result.evaluated = out.size();
    for (size_t i = 0; i < out.size(); ++i) {
        const GlintProbeOutput& o = out[i];
        bool finite = std::isfinite(o.D);
        for (int c = 0; c < 4; ++c) finite &= std::isfinite(o.footprint[c]) && std::isfinite(o.extra[c]);
        bool negative = finite && o.D < 0.0f;
        result.nonFinite += !finite;
        result.negative += negative;
        if ((!finite || negative) && result.firstBad.empty()) {
            const GlintProbeInput& in = inputs[i];
            std::ostringstream text;
            text << "D=" << o.D << " at uv (" << in.uv.x << ", " << in.uv.y << "), duvdx (" << in.duvdx.x << ", "
                 << in.duvdx.y << "), duvdy (" << in.duvdy.x << ", " << in.duvdy.y << "), h (" << in.h.x << ", " << in.h.y
                 << ", " << in.h.z << "), alpha " << in.alpha << (in.ndf ? " beckmann" : " ggx") << ", density scale "
                 << in.densityScale;
            result.firstBad = text.str();
        }
    }
    return result;
}

bool CheckReport::passed() const { return failedRules().empty(); }

std::vector<std::string> CheckReport::failedRules() const {
    std::vector<std::string> failed;
    for (const RuleResult& r : results)
        if (r.status == "FAIL") failed.push_back(r.rule);
    return failed;
}

const std::vector<std::string>& ruleNames() {
    static const std::vector<std::string> names = {"convergence", "furnace", "finite", "cost", "constant-time"};
    return names;
}

CheckReport checkMethod(const std::string& methodId, const CheckOptions& options) {
    const GlintMethod method = findGlintMethod(methodId);   // a copy: loading files must not move it
    for (const std::string& rule : options.rules)
        if (std::find(ruleNames().begin(), ruleNames().end(), rule) == ruleNames().end())
            throw UsageError("--rules: unknown rule '" + rule + "' (rules: convergence, furnace, finite, cost, constant-time)");
    auto wanted = [&](const char* rule) {
        return options.rules.empty() || std::find(options.rules.begin(), options.rules.end(), rule) != options.rules.end();
    };
    ParamValues defaults;   // every rule but convergence runs at the method's defaults
    CheckReport report;
    report.method = method.id;
    if (wanted("convergence")) report.results.push_back(convergenceRule(method, options));
    if (wanted("furnace") || wanted("finite")) {
        // The probe rules run compute shaders in a context of their own.
        std::unique_ptr<GLContext> context = createHeadlessContext(options.backend);
        if (wanted("furnace")) report.results.push_back(furnaceRule(method, defaults, options));
        if (wanted("finite")) report.results.push_back(finiteRule(method, defaults, options));
    }
    if (wanted("cost") || wanted("constant-time")) {
        SceneTiming top = timeScene("plane90", method, defaults, options);
        SceneTiming grazing = timeScene("plane25", method, defaults, options);
        if (options.progress)
            options.progress(format("lighting pass ms (smooth / method): plane90 %.2f / %.2f, plane25 %.2f / %.2f", top.smoothMs,
                                    top.methodMs, grazing.smoothMs, grazing.methodMs));
        if (wanted("cost")) {
            RuleResult r{"cost", "info", "", "reported, no limit"};
            r.measured = format("lighting pass %.2fx smooth on plane90, %.2fx on plane25 (%.0fx%.0f, wall ms around glFinish, fastest of ",
                                top.methodMs / top.smoothMs, grazing.methodMs / grazing.smoothMs, options.timingSize,
                                options.timingSize) +
                         std::to_string(options.timingFrames) + ")";
            report.results.push_back(r);
        }
        if (wanted("constant-time")) {
            RuleResult r{"constant-time", "pass", "", format("plane25/plane90 within x/÷ %.1f of smooth's", kConstantTimeBand)};
            double methodRatio = grazing.methodMs / top.methodMs, smoothRatio = grazing.smoothMs / top.smoothMs;
            double relative = methodRatio / smoothRatio;
            r.measured = format("plane25 / plane90: method %.2f, smooth %.2f, relative %.2f", methodRatio, smoothRatio, relative);
            if (!(relative <= kConstantTimeBand && relative >= 1.0 / kConstantTimeBand)) r.status = "FAIL";
            report.results.push_back(r);
        }
    }
    return report;
}

std::string formatTable(const CheckReport& report) {
    std::ostringstream out;
    out << "check-method " << report.method << "\n";
    size_t width = 13;
    out << "rule           status  measured  [limit]\n";
    for (const RuleResult& r : report.results) {
        std::string rule = r.rule;
        rule.resize(width + 2, ' ');
        std::string status = r.status;
        status.resize(6, ' ');
        out << rule << status << "  " << r.measured << "  [" << r.limit << "]\n";
    }
    std::vector<std::string> failed = report.failedRules();
    if (failed.empty()) {
        out << "all rules pass\n";
    } else {
        out << "FAILED:";
        for (const std::string& f : failed) out << " " << f;
        out << "\n";
    }
    return out.str();
}

}  // namespace glimmer::checks
