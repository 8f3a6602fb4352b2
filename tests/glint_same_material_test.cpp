// "Same material" evidence (issue 17): the one glint material rendered by every method on plane25 and plane90.
// (1) mean D / D_smooth over the highlight within 10 % of 1; (2) in the sparse case, glints per square metre
// (connected bright blobs) within a factor 2 of the expected count
//     E[glints] = sum over pixels of  density x pixel area (m^2) x pi gamma^2 D_smooth(h) (h.n),
// the facets of the pixel whose normal lies within gamma of h (a cone of solid angle pi gamma^2 holds the fraction
// pi gamma^2 D(h) (h.n) of the projected facet area, ZK16 Sec. 4.1; D&B Eq. 2). The built-in planes have UVs in
// metres, so the pixel area is |det(duv/dx, duv/dy)|; h.n is recovered from the GGX D_smooth (alpha 0.3).
// ctest asserts a representative subset at 128x128; GLIMMER_MEASURE=1 runs the full table (README).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/sparkle_stats.h"
#include "glints/glint_mapping.h"
#include "glints/methods.h"
#include "offscreen/offscreen.h"
#include "render/aov.h"
#include "support/measure.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(GlintSameMaterial, GlContext);

using namespace glimmer;

namespace {

constexpr double kPi = 3.14159265358979;
constexpr double kAlpha = 0.3;   // the built-in planes' material (engine/scene/builtin_scenes.cpp)

std::vector<float> channel(const RenderResult& r, int c) {
    std::vector<float> out(size_t(r.width) * r.height);
    for (size_t i = 0; i < out.size(); ++i) out[i] = r.hdr[4 * i + c];
    return out;
}

RenderResult render(const std::string& scene, const std::string& method, const std::string& aov, int size,
                    double density, double gamma) {
    RenderRequest request;
    request.scene = scene;
    request.environment = "none";
    request.width = request.height = size;
    request.settings.method = method;
    request.settings.apply("material.glint_density=" + std::to_string(density));
    request.settings.apply("material.glint_angular_size=" + std::to_string(gamma));
    request.settings.debugView = findAov(aov).viewId;
    // wang2020's DPF tables at 45x45x90, as in every wang2020 test (generated in 5-7 s once, not 25-60 s).
    if (method == "wang2020") {
        setenv("GLIMMER_DPF_CACHE", GLIMMER_TEST_OUTPUT_DIR "/wang2020_dpf_cache", 0);
        request.settings.apply("wang2020.table_scale=2");
    }
    return renderOffscreen(request);
}

// The smooth glint AOV plus the pixel areas and h.n, shared by every method of one scene and size.
struct SmoothFrame {
    std::vector<float> d, area, cosH;
};

SmoothFrame smoothFrame(const std::string& scene, int size) {
    SmoothFrame f;
    f.d = channel(render(scene, "smooth", "glint", size, 1e6, 0.015), 0);
    RenderResult dx = render(scene, "smooth", "duvdx", size, 1e6, 0.015);
    RenderResult dy = render(scene, "smooth", "duvdy", size, 1e6, 0.015);
    f.area.resize(f.d.size());
    f.cosH.resize(f.d.size());
    const double a2 = kAlpha * kAlpha;
    for (size_t i = 0; i < f.d.size(); ++i) {
        f.area[i] = float(std::abs(double(dx.hdr[4 * i]) * dy.hdr[4 * i + 1] - double(dx.hdr[4 * i + 1]) * dy.hdr[4 * i]));
        // GGX: D = a2 / (pi (c^2 (a2 - 1) + 1)^2)  =>  c^2 = (sqrt(a2 / (pi D)) - 1) / (a2 - 1).
        double d = f.d[i];
        double c2 = d > 0 ? (std::sqrt(a2 / (kPi * d)) - 1.0) / (a2 - 1.0) : 0.0;
        f.cosH[i] = float(std::sqrt(std::clamp(c2, 0.0, 1.0)));
    }
    return f;
}

// Connected (8-neighbour) components of pixels whose D exceeds `threshold` x D_smooth, inside the highlight
// (D_smooth >= 0.1 of its peak).
int countBlobs(const std::vector<float>& d, const std::vector<float>& smooth, int size, double threshold,
               std::vector<bool>& highlight) {
    float peak = 0;
    for (float v : smooth) peak = std::max(peak, v);
    highlight.assign(d.size(), false);
    std::vector<bool> bright(d.size(), false);
    for (size_t i = 0; i < d.size(); ++i) {
        highlight[i] = smooth[i] >= 0.1f * peak;
        bright[i] = highlight[i] && d[i] > threshold * smooth[i];
    }
    std::vector<int> stack;
    int blobs = 0;
    for (int start = 0; start < int(d.size()); ++start) {
        if (!bright[size_t(start)]) continue;
        ++blobs;
        bright[size_t(start)] = false;
        stack.push_back(start);
        while (!stack.empty()) {
            int p = stack.back();
            stack.pop_back();
            int x = p % size, y = p / size;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= size || ny >= size) continue;
                    size_t q = size_t(ny) * size + nx;
                    if (bright[q]) bright[q] = false, stack.push_back(int(q));
                }
        }
    }
    return blobs;
}

struct Row {
    std::string method, scene;
    double density, gamma, meanRatio, blobs, expected, predicted;
};

// How many times a reflecting facet is counted as a blob (D > 2 D_smooth) by each method, per pixel, given the
// pixel's expected reflecting facets lambda (the naive count above) and its footprint AOV (README "The glint
// material", sparse count):
// Each method counts the facets its material mapping gives it (methodFacetShare: deliot2023 a fifth, kemppinen2025
// a tenth of the material's since issue 36), so lambda below is the method's own expected count.
//  - deliot2023: LOD levels and grids blend by distributing the binomial over sub-areas (Eq. 8-10, Sec. 5.2,
//    6.1), so there a facet is drawn once at full weight; but Eq. 14 lerps the realizations of the 4 angular cells around h with bilinear weights
//    (u or 1 - u)(v or 1 - v), like zirr2016's levels: each cell counts where its weight exceeds 2 lambda, for u, v
//    uniform 4 P(u v > 2 lambda) = 4 (1 - c + c ln c), c = 2 lambda. (Not modelled: the per-vertex log-normal
//    spread of the count and the 3 simplex vertices, whose glints touch and merge.)
//  - zirr2016: LOD levels lerp two independent realizations (ZK16; D&B Fig. 2 "ghosting"): a facet of the level
//    of weight w is bright when w / lambda > 2, so each level counts where its weight exceeds 2 lambda.
//  - kemppinen2025: Gaussian lobes (angular alpha*, spatial pixel filter f px, Algorithm 1): a facet at angular
//    offset theta and spatial offset d from the pixel centre gives (1 / lambda) g_s(d) exp(-theta^2 / (2 alpha*^2)),
//    g_s(d) = exp(-d^2 / (2 f^2)) / (2 pi f^2); bright inside theta^2 < 2 alpha*^2 ln(g_s(d) / (2 lambda)), whose
//    solid angle over the cone's pi gamma^2 = 2 pi alpha*^2 is ln(g_s(d) / (2 lambda)); averaged over d uniform in
//    the pixel (E[d^2] = 1/6): ln(1 / (2 pi f^2)) - 1 / (12 f^2) - ln(2 lambda), at least 0.
//  - wang2020: micro scale (E = N a(A) < 4, Sec. 4.3) tests each particle (1); meso pixels show (particles in A) x
//    P, so a pixel is bright when its Poisson(E) particle count exceeds 2 E (no single glint is resolved).
double poissonTailAbove(double mean, double k) {   // P(n > k), n ~ Poisson(mean)
    double term = std::exp(-mean), cdf = 0.0;
    for (int n = 0; n <= int(std::floor(k)); ++n) cdf += term, term *= mean / double(n + 1);
    return std::max(0.0, 1.0 - cdf);
}

// The method's facets per facet of the material, from its material mapping (1 for a method that takes the density
// as it is): the mean count exp(log_density + sigma^2 / 2), the points or particles per UV area, over the density.
double methodFacetShare(const std::string& method, double density, double gamma) {
    Material m;
    m.alpha = float(kAlpha);
    m.glinty = true;
    m.glint.density = float(density);
    m.glint.angularSize = float(gamma);
    ParamValues p = materialParams(findGlintMethod(method), m, {});
    if (method == "deliot2023")
        return std::exp(p.at("log_density") + 0.5 * p.at("density_randomization") * p.at("density_randomization")) / density;
    if (method == "zirr2016") return std::exp(p.at("log_density")) / density;
    if (method == "kemppinen2025") return p.at("density") / density;
    if (method == "wang2020") return p.at("particles") / density;
    return 1.0;
}

double countedPerFacet(const std::string& method, double lambda, const float* footprint) {
    if (method == "deliot2023") {
        double c = std::min(2.0 * lambda, 1.0);
        return c > 0.0 ? 4.0 * (1.0 - c + c * std::log(c)) : 4.0;
    }
    if (method == "zirr2016") {
        double t = footprint[1] - std::floor(double(footprint[1]));   // G: the continuous LOD
        return double(1.0 - t > 2.0 * lambda) + double(t > 2.0 * lambda);
    }
    if (method == "kemppinen2025") {
        const double f = 0.7;   // filter_size default
        return std::max(0.0, std::log(1.0 / (2.0 * kPi * f * f)) - 1.0 / (12.0 * f * f) - std::log(2.0 * lambda));
    }
    return 1.0;
}

Row measure(const std::string& method, const std::string& scene, const SmoothFrame& smooth, int size, double density,
            double gamma, bool sparse) {
    RenderResult r = render(scene, method, "glint", size, density, gamma);
    EXPECT_EQ(r.stats["counts"]["non_finite_values"].get<size_t>(), 0u);
    std::vector<float> d = channel(r, 0);
    Row row{method, scene, density, gamma, sparkleStats(d, smooth.d).meanRatio, -1, -1, -1};
    if (sparse) {
        std::vector<bool> highlight;
        row.blobs = countBlobs(d, smooth.d, size, 2.0, highlight);
        RenderResult footprint = render(scene, method, "footprint", size, density, gamma);
        double expected = 0, predicted = 0;
        const double share = methodFacetShare(method, density, gamma);
        for (size_t i = 0; i < d.size(); ++i) {
            if (!highlight[i]) continue;
            double lambda = density * smooth.area[i] * kPi * gamma * gamma * smooth.d[i] * smooth.cosH[i];
            expected += lambda;
            const float* fp = &footprint.hdr[4 * i];
            if (method == "wang2020" && fp[0] >= 4.0f) predicted += poissonTailAbove(fp[0], 2.0 * fp[0]);
            else predicted += share * lambda * countedPerFacet(method, share * lambda, fp);
        }
        row.expected = expected;
        row.predicted = predicted;
    }
    std::printf("| %s | %s | %.3g | %.3g | %.3f | %s |\n", method.c_str(), scene.c_str(), density, gamma, row.meanRatio,
                sparse ? (std::to_string(int(row.blobs)) + " / " + std::to_string(int(std::lround(row.expected))) + " / " +
                          std::to_string(int(std::lround(row.predicted)))).c_str() : "-");
    return row;
}

bool measureAll() { return test::fullMeasurement(); }

}  // namespace

// Sparse, medium and dense (facets per m^2) and two angular sizes (radians). Sparse: at gamma 0.01 about 0.02
// glints per 128-px pixel of plane90 at the highlight's peak, so blobs rarely touch.
const double kSparse = 1e5, kMedium = 3e6, kDense = 1e8;

// ctest asserts a representative subset at 128x128: medium density, gamma 0.01, both planes, every method, and
// the sparse mean and count on plane90. GLIMMER_MEASURE=1: every method x plane x {sparse, medium, dense} x
// {0.01, 0.03} at 256x256 (the README table), with the same assertions.
TEST(GlintSameMaterial, EveryMethodRendersTheSameMeanAndSparseCount) {
    const bool all = measureAll();
    const int size = all ? 256 : 128;
    const std::vector<std::string> methods = {"deliot2023", "zirr2016", "kemppinen2025", "wang2020"};
    struct Case { std::string scene; double density, gamma; };
    std::vector<Case> cases;
    for (const char* scene : {"plane90", "plane25"})
        for (double density : {kSparse, kMedium, kDense})
            for (double gamma : {0.01, 0.03})
                if (all || (density == kMedium && gamma == 0.01) ||
                    (density == kSparse && gamma == 0.01 && std::string(scene) == "plane90"))
                    cases.push_back({scene, density, gamma});
    std::printf("| method | scene | density (1/m^2) | gamma (rad) | mean D / D_smooth | blobs / naive / per-method |\n"
                "|---|---|---|---|---|---|\n");
    std::string lastScene;
    SmoothFrame smooth;
    for (const Case& c : cases) {
        if (c.scene != lastScene) smooth = smoothFrame(c.scene, size), lastScene = c.scene;
        for (const std::string& method : methods) {
            const bool sparse = c.density == kSparse;
            Row row = measure(method, c.scene, smooth, size, c.density, c.gamma, sparse);
            std::string what = method + " " + c.scene + " density " + std::to_string(c.density) + " gamma " +
                               std::to_string(c.gamma);
            // wang2020 was 1.19-1.27 x smooth while its DPF tables were Beckmann under these GGX planes; they now
            // follow the material's NDF (engine/glints/wang2020/wang2020_dpf.h ParticleNdf), so the 10 % target holds.
            // In the sparse case the highlight holds about `expected` reflecting facets of the material, so even
            // the material's own mean over it is known to 1 / sqrt(expected) only (7.8 % at 165); methods whose
            // mapping gives them the material's variance (issue 36) get that spread, 3 standard deviations.
            double tolerance = sparse ? std::max(0.10, 3.0 / std::sqrt(std::max(row.expected, 1.0))) : 0.10;
            EXPECT_NEAR(row.meanRatio, 1.0, tolerance) << what;
            // Issue 17's factor-2 count criterion against each method's predicted count (countedPerFacet above);
            // the naive count (every reflecting facet once) is printed beside it. Not for deliot2023 and
            // kemppinen2025 since issue 36 mapped them to the material's statistics (a fifth and a tenth of the
            // facets, no density randomization, deliot2023's hard gate): these per-blob models were fitted to
            // the earlier mapping; the methods are judged against the discrete-facet reference's block
            // statistics instead (docs/glint_statistics.md), and their counts are printed here.
            const bool remapped = method == "deliot2023" || method == "kemppinen2025";
            if (sparse && row.predicted >= 30.0 && !remapped) {
                EXPECT_GE(row.blobs, 0.5 * row.predicted) << what;
                EXPECT_LE(row.blobs, 2.0 * row.predicted) << what;
            } else if (sparse && remapped) {
                std::printf("  %s: %d blobs, naive %.0f, per-method model %.0f (reported)\n", what.c_str(),
                            int(row.blobs), row.expected, row.predicted);
            } else if (sparse) {
                std::printf("  %s: predicted count %.1f too small to judge\n", what.c_str(), row.predicted);
            }
        }
    }
}

// Done-when of issue 17: a glTF with one glinty material (content/models/glint_sample.gltf) glints on that
// material only, lit by its own lights: the glint AOV (first light = the model's spot) of deliot2023 equals
// smooth on the box's pixels and differs from it on the floor's.
TEST(GlintSameMaterial, OnlyTheGlintyMaterialOfAModelGlints) {
    auto renderModel = [](const std::string& method, const std::string& aov) {
        RenderRequest request;
        request.scene = std::string(GLIMMER_TEST_DIR) + "/../content/models/glint_sample.gltf";
        request.camera = "view";
        request.environment = "none";
        request.width = request.height = 128;
        request.settings.method = method;
        request.settings.debugView = findAov(aov).viewId;
        return renderOffscreen(request);
    };
    RenderResult ids = renderModel("smooth", "material");
    std::vector<float> smooth = channel(renderModel("smooth", "glint"), 0);
    std::vector<float> glinty = channel(renderModel("deliot2023", "glint"), 0);
    size_t boxPixels = 0, boxDifferent = 0, floorLit = 0, floorDifferent = 0;
    for (size_t i = 0; i < smooth.size(); ++i) {
        if (ids.hdr[4 * i + 3] <= 0.0f) continue;   // background
        int material = int(std::lround(ids.hdr[4 * i + 2]));
        bool different = std::abs(glinty[i] - smooth[i]) > 1e-4f * std::max(smooth[i], 1e-3f);
        if (material == 1) ++boxPixels, boxDifferent += different;
        if (material == 0 && smooth[i] > 0.05f) ++floorLit, floorDifferent += different;
    }
    EXPECT_GT(boxPixels, 500u);
    EXPECT_EQ(boxDifferent, 0u);
    ASSERT_GT(floorLit, 500u);   // the spot lights the floor
    EXPECT_GT(double(floorDifferent) / double(floorLit), 0.5);
}
