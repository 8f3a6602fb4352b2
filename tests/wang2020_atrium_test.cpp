// wang2020 in the atrium with each glinty material's own roughness and NDF (issue 16): one DPF table per distinct
// (NDF, roughness) of the glinty materials (engine/glints/wang2020/wang2020_resources.h). Court view at 256 x 256, DPF
// tables at 45x45x90 (table_scale=2, as in every wang2020 test), the materials' glint parameters mapped as for
// every method (README "The glint material"). For each glinty look: mean radiance over its pixels within 25 % of
// smooth's, and sparkle: over its sun highlight, p99 / mean of D / D_smooth (glint AOVs) above 1.3 (smooth: 1).
// The car-paint sphere's sun highlight (its brightest 5 % under smooth) is as bright on average as smooth's (25 %).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "render/aov.h"
#include "offscreen/offscreen.h"

namespace glimmer {
namespace {

double luminance(const std::vector<float>& hdr, size_t p) {
    return 0.2126 * hdr[4 * p] + 0.7152 * hdr[4 * p + 1] + 0.0722 * hdr[4 * p + 2];
}

double average(const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / double(v.size());
}

// p99 / mean: near the lobe's own contrast for a smooth highlight, raised by glints.
double peakRatio(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v[size_t(0.99 * double(v.size() - 1))] / std::max(average(v), 1e-12);
}

TEST(Wang2020Atrium, EachGlintyMaterialKeepsTheMeanAndSparkles) {
    setenv("GLIMMER_DPF_CACHE", GLIMMER_TEST_OUTPUT_DIR "/wang2020_dpf_cache", 0);
    RenderRequest request;
    request.scene = "atrium";
    request.camera = "court";
    request.width = request.height = 256;
    request.settings.method = "smooth";
    OffscreenSession session(request);
    const Scene& scene = session.scene();
    RenderRequest ids = request;
    ids.settings.debugView = findAov("material").viewId;
    std::vector<float> material = session.render(ids).hdr;
    std::vector<float> smooth = session.render(request).hdr;
    RenderRequest wang = request;
    wang.settings.method = "wang2020";
    wang.settings.apply("wang2020.table_scale=2");
    RenderResult glintResult = session.render(wang);
    EXPECT_EQ(glintResult.stats["counts"]["non_finite_values"].get<size_t>(), 0u);
    const std::vector<float>& glints = glintResult.hdr;
    // The glint AOV (D of the first light, the sun) of both, for the sparkle measure.
    RenderRequest smoothAov = request, wangAov = wang;
    smoothAov.settings.debugView = wangAov.settings.debugView = findAov("glint").viewId;
    std::vector<float> smoothD = session.render(smoothAov).hdr, wangD = session.render(wangAov).hdr;
    auto nameAt = [&](size_t p) {
        size_t id = size_t(std::lround(material[4 * p + 2]));
        return id < scene.materials.size() ? scene.materials[id].name : std::string();
    };

    struct Look { const char* label; std::set<std::string> names; };
    const Look looks[] = {{"snow", {"snow"}},
                          {"car paint", {"car_paint_red", "car_paint_blue"}},
                          {"drapes", {"drape_red", "drape_blue", "drape_green"}}};
    const size_t pixels = size_t(request.width) * request.height;
    for (const Look& look : looks) {
        std::vector<double> s, g;
        double peakD = 0.0;
        for (size_t p = 0; p < pixels; ++p)
            if (material[4 * p + 3] > 0.0f && look.names.count(nameAt(p))) {
                s.push_back(luminance(smooth, p)), g.push_back(luminance(glints, p));
                peakD = std::max(peakD, double(smoothD[4 * p]));
            }
        ASSERT_GT(s.size(), 150u) << look.label << ": too few pixels in the court view";
        // Sparkle: D / D_smooth over the look's sun highlight (D_smooth >= 0.1 of its peak there) is 1 for
        // smooth at every pixel; glints make its p99 / mean exceed 1.3.
        std::vector<double> ratio;
        for (size_t p = 0; p < pixels; ++p)
            if (material[4 * p + 3] > 0.0f && look.names.count(nameAt(p)) && smoothD[4 * p] >= 0.1 * peakD &&
                smoothD[4 * p] > 0.0f)
                ratio.push_back(double(wangD[4 * p]) / double(smoothD[4 * p]));
        ASSERT_GT(ratio.size(), 20u) << look.label << ": no sun highlight in view";
        const double meanRatio = average(g) / average(s), sparkle = peakRatio(ratio);
        std::printf("%-9s %5zu px: mean radiance wang2020 / smooth %.3f; %zu highlight px: D/D_smooth mean %.2f, "
                    "p99/mean %.2f\n", look.label, s.size(), meanRatio, ratio.size(), average(ratio), sparkle);
        EXPECT_NEAR(meanRatio, 1.0, 0.25) << look.label;
        EXPECT_GT(sparkle, 1.3) << look.label << ": no sparkle";
    }
    // The car-paint sphere (right tenth of the view; the eggs are left of the centre): its sun highlight.
    std::vector<std::pair<double, double>> sphere;
    for (int y = 0; y < request.height; ++y)
        for (int x = request.width * 9 / 10; x < request.width; ++x) {
            size_t p = size_t(y) * request.width + x;
            if (nameAt(p) == "car_paint_blue") sphere.push_back({luminance(smooth, p), luminance(glints, p)});
        }
    ASSERT_GT(sphere.size(), 60u) << "the sphere is not in the court view";
    std::sort(sphere.begin(), sphere.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    const size_t top = std::max<size_t>(sphere.size() / 20, 10);
    double sumSmooth = 0.0, sumWang = 0.0;
    for (size_t i = 0; i < top; ++i) sumSmooth += sphere[i].first, sumWang += sphere[i].second;
    std::printf("car-paint sphere highlight (%zu px): mean wang2020 / smooth %.3f\n", top, sumWang / sumSmooth);
    EXPECT_NEAR(sumWang / sumSmooth, 1.0, 0.25) << "the car-paint sphere's highlight";
}

}  // namespace
}  // namespace glimmer
