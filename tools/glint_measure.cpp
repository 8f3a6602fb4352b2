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

#include "reference/discrete_facets/block_stats.h"
#include "core/error.h"
#include "core/log.h"
#include "glints/methods.h"
#include "glints/user/user_methods.h"
#include "reference/discrete_facets/method_statistics.h"
#include "reference/discrete_facets/reference_render.h"
#include "render/aov.h"
#include "offscreen/offscreen.h"

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

    std::printf("| scene | NDF | alpha | density /m2 | gamma | facets per block | method | block | mean | CV | p99.9 / mean | dark | "
                "CV / ref | p99.9 / ref | dark - ref | 4x4 target |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const std::string& scene : o.scenes) {
        RenderRequest first = configRequest(o, scene, {"ggx", 0.3, 1e6, 0.015});
        first.settings.method = "smooth";
        OffscreenSession session(first);
        facets::SurfaceImage surface = facets::captureSurface(session, first);
        for (const Material4& m : materials(o)) {
            RenderRequest request = configRequest(o, scene, m);
            facets::GlintFrame ref = facets::referenceGlintFrame(session, surface, request);
            std::vector<std::pair<std::string, facets::GlintFrame>> frames = {{facets::kReferenceMethodId, ref}};
            for (const std::string& method : o.methods)
                frames.push_back({method, facets::methodGlintFrame(session, method, request, ref)});
            for (int block : {1, 4, 16}) {
                facets::BlockStats r = facets::blockStats(ref.d, ref.smooth, ref.inside, o.size, o.size, block);
                const double lambdaBlock = facets::meanBlockLambda(ref, block);
                for (const auto& [method, f] : frames) {
                    facets::BlockStats s = facets::blockStats(f.d, f.smooth, f.inside, o.size, o.size, block);
                    bool isRef = method == facets::kReferenceMethodId;
                    facets::TargetCheck target = facets::checkTarget(s, r);
                    std::printf("| %s | %s | %.2g | %.0e | %.3g | %.3g | %s | %dx%d | %.3f | %.3f | %.2f | %.3f | %s | %s | %s | %s |\n",
                                scene.c_str(), m.ndf.c_str(), m.alpha, m.density, m.gamma, lambdaBlock, method.c_str(), block, block,
                                s.mean, s.cv, s.p999OverMean, s.darkFraction,
                                isRef ? "-" : (r.cv > 0 ? std::to_string(s.cv / r.cv).substr(0, 5).c_str() : "-"),
                                isRef ? "-" : (r.p999OverMean > 0 ? std::to_string(s.p999OverMean / r.p999OverMean).substr(0, 5).c_str() : "-"),
                                isRef ? "-" : std::to_string(s.darkFraction - r.darkFraction).substr(0, 6).c_str(),
                                isRef || block != 4 ? "" : (target.all() ? "yes" : "no"));
                    if (json.is_open())
                        json << "{\"scene\":\"" << scene << "\",\"ndf\":\"" << m.ndf << "\",\"alpha\":" << m.alpha
                             << ",\"density\":" << m.density << ",\"gamma\":" << m.gamma << ",\"method\":\"" << method
                             << "\",\"block\":" << block << ",\"lambda\":" << lambdaBlock << ",\"blocks\":" << s.blocks << ",\"mean\":" << s.mean
                             << ",\"cv\":" << s.cv << ",\"p999\":" << s.p999OverMean << ",\"dark\":" << s.darkFraction
                             << "}\n";
                }
            }
            std::fflush(stdout);
            if (json.is_open()) json.flush();   // a run cut short keeps every finished view
        }
        if (o.lifespan)
            for (double gamma : o.gammas) {
                RenderRequest base = configRequest(o, scene, {"ggx", 0.3, 1e6, gamma});
                std::printf("\nlifespan %s gamma %.3g (degrees of light turn where the correlation halves):", scene.c_str(), gamma);
                std::vector<std::string> all = {facets::kReferenceMethodId};
                all.insert(all.end(), o.methods.begin(), o.methods.end());
                for (const std::string& method : all) {
                    double deg = facets::lifespanDegrees(session, surface, base, method);
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
