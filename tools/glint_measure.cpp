// glint_measure: every glint method measured against the exact discrete-facet reference (issue 36,
// docs/glint_statistics.md). For each scene and glint material it renders the glint AOV (the first light's D,
// `--env none`) of smooth and of each method, counts the reference's facets on the CPU from the same G-buffer
// (engine/reference/discrete_facets/), and prints one Markdown row per (material, method, block size): statistics
// of sum(D) / sum(D_smooth) over 1x1, 4x4 and 16x16 blocks inside the highlight (mean, CV, p99.9 / mean, dark
// fraction), with the 4x4 ratios to the reference and whether the target holds (CV and p99.9 / mean
// within 1.5x, dark fraction within 0.1, mean within 5 %). --lifespan adds the angular lifespan: the light turned
// about +y in small steps, the angle at which the per-pixel correlation of D / D_smooth with the unturned frame
// falls to 0.5, for each method and the reference.
//
// Any method id of the method table is accepted (built-ins, file:PATH.glsl user methods).
// usage: glint_measure [--scenes a,b] [--methods a,b] [--densities ...] [--gammas ...] [--ndfs ggx,beckmann]
//                      [--alphas ...] [--design oat|cross] [--size N] [--lifespan] [--set KEY=V ...]
//                      [--reference-set KEY=V ...] [--threads N] [--json FILE]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/sparkle_stats.h"
#include "core/error.h"
#include "core/log.h"
#include "glints/methods.h"
#include "glints/user_methods.h"
#include "reference/discrete_facets/reference_render.h"
#include "render/aov.h"
#include "render/offscreen.h"

using namespace glimmer;

namespace {

std::vector<std::string> split(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

std::vector<double> numbers(const std::string& text, const char* flag) {
    std::vector<double> out;
    for (const std::string& item : split(text)) {
        char* end = nullptr;
        double v = std::strtod(item.c_str(), &end);
        if (*end != '\0' || !std::isfinite(v)) throw UsageError(std::string(flag) + ": '" + item + "' is not a number");
        out.push_back(v);
    }
    return out;
}

struct Material4 {
    std::string ndf;
    double alpha, density, gamma;
};

struct Options {
    std::vector<std::string> scenes = {"plane90", "plane25", "sphere", "atrium"};
    std::vector<std::string> methods = {"deliot2023", "zirr2016", "kemppinen2025", "wang2020"};
    std::vector<double> densities = {1e4, 1e5, 1e6, 1e7, 1e8}, gammas = {0.005, 0.015, 0.05}, alphas = {0.1, 0.3, 0.6};
    std::vector<std::string> ndfs = {"ggx", "beckmann"};
    std::string design = "oat";
    int size = 384;
    bool lifespan = false;
    std::vector<std::string> sets, referenceSets;
    std::string json;
    int threads = 0;
};

// The materials measured. "oat" (one factor at a time around GGX, alpha 0.3): density x gamma crossed, then each
// other NDF and alpha at density 1e6 and gamma 0.015. "cross": every combination.
std::vector<Material4> materials(const Options& o) {
    std::vector<Material4> out;
    if (o.design == "cross") {
        for (const std::string& ndf : o.ndfs)
            for (double a : o.alphas)
                for (double d : o.densities)
                    for (double g : o.gammas) out.push_back({ndf, a, d, g});
        return out;
    }
    for (double d : o.densities)
        for (double g : o.gammas) out.push_back({"ggx", 0.3, d, g});
    for (const std::string& ndf : o.ndfs)
        for (double a : o.alphas)
            if (!(ndf == "ggx" && a == 0.3)) out.push_back({ndf, a, 1e6, 0.015});
    return out;
}

std::vector<float> firstChannel(const RenderResult& r) {
    std::vector<float> out(size_t(r.width) * size_t(r.height));
    for (size_t i = 0; i < out.size(); ++i) out[i] = r.hdr[4 * i];
    return out;
}

RenderRequest configRequest(const Options& o, const std::string& scene, const Material4& m) {
    RenderRequest r;
    r.scene = scene;
    r.environment = "none";
    r.width = r.height = o.size;
    r.settings.debugView = findAov("glint").viewId;
    for (const std::string& s : o.sets) r.settings.apply(s);
    for (const std::string& s : o.referenceSets) r.settings.apply("reference." + s);
    r.settings.apply("material.ndf=" + m.ndf);
    char text[64];
    std::snprintf(text, sizeof text, "material.alpha=%.9g", m.alpha);
    r.settings.apply(text);
    std::snprintf(text, sizeof text, "material.glint_density=%.9g", m.density);
    r.settings.apply(text);
    std::snprintf(text, sizeof text, "material.glint_angular_size=%.9g", m.gamma);
    r.settings.apply(text);
    return r;
}

// The glint AOV of `method` (the reference counted on the CPU from `surface`) and smooth's.
struct Frame {
    std::vector<float> d, smooth;
    std::vector<bool> inside;
};

Frame referenceFrame(OffscreenSession& session, const facets::SurfaceImage& surface, const RenderRequest& request) {
    RenderRequest smooth = request;
    smooth.settings.method = "smooth";
    Frame f;
    f.smooth = firstChannel(session.render(smooth));   // also leaves the request's materials and lights in the scene
    facets::ReferenceOptions options = facets::referenceOptions(request.settings);
    options.maxLights = 1;
    options.progress = false;
    facets::ReferenceImage image = facets::evaluateLights(surface, session.scene().materials, session.scene().lights, options);
    f.d.assign(f.smooth.size(), 0.0f);
    f.inside = highlightMask(f.smooth);
    for (size_t i = 0; i < f.d.size(); ++i) {
        if (image.lights == 0) break;
        glm::vec3 d = image.d[i * size_t(image.lights)];
        float cpuSmooth = image.smoothD[i * size_t(image.lights)];
        // The CPU normalized to its own D(h) (rebuilt from the AOVs); expressed over the GPU's smooth D so every
        // column divides by the same image.
        float ratio = cpuSmooth > 0.0f ? (d.x + d.y + d.z) / (3.0f * cpuSmooth) : 0.0f;
        f.d[i] = ratio * f.smooth[i];
        f.inside[i] = f.inside[i] && image.glinty[i];
    }
    return f;
}

Frame methodFrame(OffscreenSession& session, const std::string& method, const RenderRequest& request, const Frame& ref) {
    RenderRequest r = request;
    r.settings.method = method;
    RenderResult result = session.render(r);
    if (result.stats["counts"]["non_finite_values"].get<size_t>() != 0)
        log::warn("glint_measure: ", method, " wrote non-finite values");
    Frame f = ref;
    f.d = firstChannel(result);
    return f;
}

const char* verdict(const BlockStats& m, const BlockStats& ref) {
    bool cv = ref.cv > 0 ? (m.cv / ref.cv <= 1.5 && m.cv / ref.cv >= 1 / 1.5) : m.cv < 0.05;
    bool p = ref.p999OverMean > 0 ? (m.p999OverMean / ref.p999OverMean <= 1.5 && m.p999OverMean / ref.p999OverMean >= 1 / 1.5) : true;
    bool dark = std::abs(m.darkFraction - ref.darkFraction) <= 0.1;
    bool mean = std::abs(m.mean / ref.mean - 1.0) <= 0.05;
    return cv && p && dark && mean ? "yes" : "no";
}

double pearson(const std::vector<float>& a, const std::vector<float>& b, const std::vector<bool>& mask) {
    double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!mask[i]) continue;
        n += 1, sa += a[i], sb += b[i], saa += double(a[i]) * a[i], sbb += double(b[i]) * b[i], sab += double(a[i]) * b[i];
    }
    if (n < 2) return 0.0;
    double va = saa / n - (sa / n) * (sa / n), vb = sbb / n - (sb / n) * (sb / n);
    return va > 0 && vb > 0 ? (sab / n - (sa / n) * (sb / n)) / std::sqrt(va * vb) : 0.0;
}

std::vector<float> ratios(const Frame& f) {
    std::vector<float> r(f.d.size(), 0.0f);
    for (size_t i = 0; i < r.size(); ++i) r[i] = f.inside[i] && f.smooth[i] > 0 ? f.d[i] / f.smooth[i] : 0.0f;
    return r;
}

// The light-turn angle (degrees) at which the per-pixel correlation of D / D_smooth halves.
double lifespan(OffscreenSession& session, const facets::SurfaceImage& surface, const RenderRequest& base,
                const std::string& method) {
    auto frameAt = [&](double degrees) {
        RenderRequest r = base;
        char text[64];
        std::snprintf(text, sizeof text, "light.turn=%.9g", degrees);
        r.settings.apply(text);
        Frame ref = referenceFrame(session, surface, r);
        return method == facets::kReferenceMethodId ? ref : methodFrame(session, method, r, ref);
    };
    Frame f0 = frameAt(0.0);
    std::vector<float> r0 = ratios(f0);
    double previousAngle = 0.0, previous = 1.0;
    for (double degrees = 0.02; degrees <= 20.0; degrees *= 1.5) {
        Frame f = frameAt(degrees);
        std::vector<bool> both(f.inside.size());
        for (size_t i = 0; i < both.size(); ++i) both[i] = f.inside[i] && f0.inside[i];
        double rho = pearson(r0, ratios(f), both);
        if (rho <= 0.5) return previousAngle + (previous - 0.5) / (previous - rho) * (degrees - previousAngle);
        previousAngle = degrees;
        previous = rho;
    }
    return INFINITY;
}

int run(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw UsageError(a + ": missing value");
            return argv[++i];
        };
        if (a == "--scenes") o.scenes = split(next());
        else if (a == "--methods") o.methods = split(next());
        else if (a == "--densities") o.densities = numbers(next(), "--densities");
        else if (a == "--gammas") o.gammas = numbers(next(), "--gammas");
        else if (a == "--alphas") o.alphas = numbers(next(), "--alphas");
        else if (a == "--ndfs") o.ndfs = split(next());
        else if (a == "--design") o.design = next();
        else if (a == "--size") o.size = std::atoi(next().c_str());
        else if (a == "--lifespan") o.lifespan = true;
        else if (a == "--set") o.sets.push_back(next());
        else if (a == "--reference-set") o.referenceSets.push_back(next());
        else if (a == "--json") o.json = next();
        else if (a == "--help") {
            std::puts("usage: glint_measure [--scenes a,b] [--methods a,b|file:PATH.glsl] [--densities ...] [--gammas ...]\n"
                      "       [--ndfs ggx,beckmann] [--alphas ...] [--design oat|cross] [--size N] [--lifespan]\n"
                      "       [--set KEY=V ...] [--reference-set lobe=gaussian ...] [--json FILE]");
            return 0;
        } else throw UsageError("unknown option '" + a + "' (--help)");
    }
    if (o.size < 16 || o.size > 4096) throw UsageError("--size: expected 16 .. 4096");
    if (o.design != "oat" && o.design != "cross") throw UsageError("--design: oat or cross");
    facets::registerReferenceMethod();
    for (std::string& m : o.methods) m = resolveGlintMethod(m, "--methods");
    std::ofstream json;
    if (!o.json.empty()) json.open(o.json);

    std::printf("| scene | NDF | alpha | density /m2 | gamma | method | block | mean | CV | p99.9 / mean | dark | CV / ref | "
                "p99.9 / ref | dark - ref | 4x4 target |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string& scene : o.scenes) {
        RenderRequest first = configRequest(o, scene, {"ggx", 0.3, 1e6, 0.015});
        first.settings.method = "smooth";
        OffscreenSession session(first);
        facets::SurfaceImage surface = facets::captureSurface(session, first);
        for (const Material4& m : materials(o)) {
            RenderRequest request = configRequest(o, scene, m);
            Frame ref = referenceFrame(session, surface, request);
            std::vector<std::pair<std::string, Frame>> frames = {{facets::kReferenceMethodId, ref}};
            for (const std::string& method : o.methods) frames.push_back({method, methodFrame(session, method, request, ref)});
            for (int block : {1, 4, 16}) {
                BlockStats r = blockStats(ref.d, ref.smooth, ref.inside, o.size, o.size, block);
                for (const auto& [method, f] : frames) {
                    BlockStats s = blockStats(f.d, f.smooth, f.inside, o.size, o.size, block);
                    bool isRef = method == facets::kReferenceMethodId;
                    std::printf("| %s | %s | %.2g | %.0e | %.3g | %s | %dx%d | %.3f | %.3f | %.2f | %.3f | %s | %s | %s | %s |\n",
                                scene.c_str(), m.ndf.c_str(), m.alpha, m.density, m.gamma, method.c_str(), block, block,
                                s.mean, s.cv, s.p999OverMean, s.darkFraction,
                                isRef ? "-" : (r.cv > 0 ? std::to_string(s.cv / r.cv).substr(0, 5).c_str() : "-"),
                                isRef ? "-" : (r.p999OverMean > 0 ? std::to_string(s.p999OverMean / r.p999OverMean).substr(0, 5).c_str() : "-"),
                                isRef ? "-" : std::to_string(s.darkFraction - r.darkFraction).substr(0, 6).c_str(),
                                isRef || block != 4 ? "" : verdict(s, r));
                    if (json.is_open())
                        json << "{\"scene\":\"" << scene << "\",\"ndf\":\"" << m.ndf << "\",\"alpha\":" << m.alpha
                             << ",\"density\":" << m.density << ",\"gamma\":" << m.gamma << ",\"method\":\"" << method
                             << "\",\"block\":" << block << ",\"blocks\":" << s.blocks << ",\"mean\":" << s.mean
                             << ",\"cv\":" << s.cv << ",\"p999\":" << s.p999OverMean << ",\"dark\":" << s.darkFraction
                             << "}\n";
                }
            }
            std::fflush(stdout);
        }
        if (o.lifespan)
            for (double gamma : o.gammas) {
                RenderRequest base = configRequest(o, scene, {"ggx", 0.3, 1e6, gamma});
                std::printf("\nlifespan %s gamma %.3g (degrees of light turn where the correlation halves):", scene.c_str(), gamma);
                std::vector<std::string> all = {facets::kReferenceMethodId};
                all.insert(all.end(), o.methods.begin(), o.methods.end());
                for (const std::string& method : all) {
                    double deg = lifespan(session, surface, base, method);
                    std::printf(" %s %.3g;", method.c_str(), deg);
                    if (json.is_open())
                        json << "{\"scene\":\"" << scene << "\",\"gamma\":" << gamma << ",\"method\":\"" << method
                             << "\",\"lifespan_deg\":" << deg << "}\n";
                    std::fflush(stdout);
                }
                std::printf("\n\n");
            }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const UsageError& e) {
        std::fprintf(stderr, "glint_measure: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "glint_measure: %s\n", e.what());
        return 1;
    }
}
