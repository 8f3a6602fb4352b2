// Statistics every glint method is measured by (issue 16): how long a glint lives as the light turns (angular
// lifespan, against what each method's parameters predict) and whether the counting statistics hold for any pixel
// footprint (footprint consistency: a pixel of an N-pixel render against a 4x4 box of a 4N-pixel render).
// Rendered in process through the real pipeline (glint AOV = the first light's D, `--env none`).
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "bench/sparkle_stats.h"
#include "glints/glint_mapping.h"
#include "glints/methods.h"
#include "offscreen/offscreen.h"
#include "reference/kemppinen2025_reference.h"
#include "render/aov.h"
#include "scene/builtin_scenes.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(GlintLifespan, GlContext);
GLIMMER_SUITE_NEEDS(GlintFootprint, GlContext);

using namespace glimmer;

namespace {

std::vector<float> renderGlintD(const std::string& scene, const std::string& method, int size,
                                const std::vector<std::string>& sets = {}) {
    RenderRequest request;
    request.scene = scene;
    request.environment = "none";
    request.width = request.height = size;
    request.settings.method = method;
    for (const std::string& s : sets) request.settings.apply(s);
    request.settings.debugView = findAov("glint").viewId;
    RenderResult r = renderOffscreen(request);
    EXPECT_EQ(r.stats["counts"]["non_finite_values"].get<size_t>(), 0u) << method << " " << scene;
    std::vector<float> d(size_t(size) * size);
    for (size_t i = 0; i < d.size(); ++i) d[i] = r.hdr[4 * i];
    return d;
}

// plane90's light (engine/scene/builtin_scenes.cpp) turned by `angle` radians about the world z axis: with the
// camera looking straight down, h moves along the plane's x (u) axis at about half the light's angle.
glm::vec3 plane90Light(double angle) {
    glm::vec3 l = glm::normalize(glm::vec3(0.25f, 1.0f, 0.15f));
    float c = float(std::cos(angle)), s = float(std::sin(angle));
    return {c * l.x - s * l.y, s * l.x + c * l.y, l.z};
}

std::string plane90SceneWithLight(const std::string& dir, double angle) {
    glm::vec3 l = plane90Light(angle);
    std::string path = dir + "/plane90_light_" + std::to_string(angle) + ".json";
    std::ofstream(path) << "{\"base\": \"plane90\", \"lights\": [{\"type\": \"directional\", \"direction\": [" << l.x
                        << ", " << l.y << ", " << l.z << "], \"intensity\": 1}]}\n";
    return path;
}

// Pearson correlation of a and b over the pixels where mask is set.
double correlation(const std::vector<float>& a, const std::vector<float>& b, const std::vector<bool>& mask) {
    double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        if (!mask[i]) continue;
        n += 1, sa += a[i], sb += b[i], saa += double(a[i]) * a[i], sbb += double(b[i]) * b[i], sab += double(a[i]) * b[i];
    }
    double va = saa / n - (sa / n) * (sa / n), vb = sbb / n - (sb / n) * (sb / n);
    return va > 0 && vb > 0 ? (sab / n - (sa / n) * (sb / n)) / std::sqrt(va * vb) : 0.0;
}

// Half vector of the image centre (view straight up, +y) in plane90's shading frame (x, z tangent; y normal),
// returned as (tangent x, tangent z, normal).
glm::dvec3 centreHalfVector(double angle) {
    glm::dvec3 h = glm::normalize(glm::dvec3(plane90Light(angle)) + glm::dvec3(0, 1, 0));
    return {h.x, h.z, h.y};
}

// The light angle at which `distance(angle)` (increasing) reaches `target`, by bisection on [0, 0.5] rad.
template <class F>
double angleWhere(F distance, double target) {
    double lo = 0.0, hi = 0.5;
    for (int i = 0; i < 60; ++i) {
        double mid = 0.5 * (lo + hi);
        (distance(mid) < target ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

struct Lifespan {
    double measured = 0, predicted = 0;
};

// D / D_smooth per pixel of plane90 with the light turned by `angle` (the smooth profile moves with the light:
// correlating D itself would count the highlight's shape as a glint that never dies).
std::vector<float> glintRatio(const std::string& dir, double angle, const std::string& method,
                              const std::vector<std::string>& sets, int size, std::vector<bool>* mask = nullptr) {
    std::string scene = plane90SceneWithLight(dir, angle);
    std::vector<float> d = renderGlintD(scene, method, size, sets), smooth = renderGlintD(scene, "smooth", size);
    float peak = 0;
    for (float v : smooth) peak = std::max(peak, v);
    if (mask) mask->assign(smooth.size(), false);
    for (size_t i = 0; i < d.size(); ++i) {
        bool lit = smooth[i] >= 0.1f * peak;
        d[i] = lit ? d[i] / smooth[i] : 0.0f;
        if (mask) (*mask)[i] = lit;
    }
    return d;
}

// Renders plane90 at 96x96 with the light turned in steps, correlates each frame's per-pixel D / D_smooth with the
// unturned frame's over the highlight (smooth D >= 0.1 of its peak) and returns the angle where the correlation
// falls to 0.5 (linear interpolation between steps).
double measuredHalfAngle(const std::string& method, const std::vector<std::string>& sets,
                         const std::vector<double>& angles) {
    std::string dir = test::makeTempDir("lifespan_" + method);
    const int size = 96;
    std::vector<bool> mask;
    std::vector<float> base = glintRatio(dir, 0.0, method, sets, size, &mask);
    double previousAngle = 0, previous = 1;
    for (double angle : angles) {
        std::vector<bool> turnedMask;
        std::vector<float> turned = glintRatio(dir, angle, method, sets, size, &turnedMask);
        for (size_t i = 0; i < mask.size(); ++i) turnedMask[i] = turnedMask[i] && mask[i];
        double rho = correlation(base, turned, turnedMask);
        std::printf("%s: light turned %.4f rad, correlation %.3f\n", method.c_str(), angle, rho);
        if (rho <= 0.5) return previousAngle + (previous - 0.5) / (previous - rho) * (angle - previousAngle);
        previousAngle = angle;
        previous = rho;
    }
    return angles.back() * 2;   // never halved within the steps: report beyond the range (fails the check)
}

}  // namespace

// deliot2023: each spatial vertex's count is a bilinear blend over the hemispherical grid's cells (Eq. 14) of
// independent draws, so its correlation under a shift s (in cells, along a grid axis) is the autocorrelation of
// the tent: 1 - 1.5 s^2 + 0.75 s^3, 0.5 at s = 0.72. The grid is indexed by the projected h, whose cell is R
// (`angular_grid=projected`, default) or sqrt(R / D(n)) (`lobe`); h turns at about half the light's angle. The
// prediction solves |h.xy(angle) - h.xy(0)| = 0.72 cell at the image centre. Measured within 3 % of it (0.00719 vs
// 0.00731 rad projected, 0.0529 vs 0.0549 lobe); asserted within a factor 1.5 both ways.
TEST(GlintLifespan, Deliot2023HalvesWhereTheAngularCellPredicts) {
    // R as the shader reads it: mapped from plane90's glint material, (gamma / alpha)^2 (glint_mapping.h).
    const Material plane = makeBuiltinScene("plane90").materials.front();
    const double alpha = plane.alpha;
    const double R = materialParams(findGlintMethod("deliot2023"), plane, {}).at("microfacet_roughness");
    const double Dn = 1.0 / (M_PI * alpha * alpha);
    for (bool projected : {true, false}) {
        double cell = projected ? R : std::sqrt(R / Dn);
        glm::dvec3 h0 = centreHalfVector(0.0);
        double predicted = angleWhere(
            [&](double a) { return glm::length(glm::dvec2(centreHalfVector(a)) - glm::dvec2(h0)); }, 0.72 * cell);
        std::vector<double> angles;
        for (int i = 1; i <= 8; ++i) angles.push_back(predicted * 0.35 * i);
        std::vector<std::string> sets = {std::string("deliot2023.angular_grid=") + (projected ? "projected" : "lobe")};
        double measured = measuredHalfAngle("deliot2023", sets, angles);
        std::printf("deliot2023 angular_grid=%s: correlation halves at %.5f rad (%.3f deg), predicted %.5f rad\n",
                    projected ? "projected" : "lobe", measured, measured * 180 / M_PI, predicted);
        EXPECT_GT(measured / predicted, 1 / 1.5) << (projected ? "projected" : "lobe");
        EXPECT_LT(measured / predicted, 1.5) << (projected ? "projected" : "lobe");
    }
}

// kemppinen2025: every glint is a Gaussian lobe of standard deviation sigma_a = alpha* sqrt(d) in the prior space
// (Sigma_a of Algorithm 1; d = pi D(h) by default, D(h) with angular_covariance=d); the correlation of a sum of such
// lobes under a shift delta is exp(-delta^2 / (4 sigma_a^2)), 0.5 at delta = 1.665 sigma_a. The prediction maps the
// centre's h through the method's own T (CPU reference) and solves |T(h(angle)) - T(h(0))| = 1.665 sigma_a.
// The explicit sum covers only the k nearest angular cells, and that window jumps as h moves (points enter and leave
// it, traded against the smooth compensation), which adds decorrelation: measured 0.50 (d = pi D) and 0.68 (d = D)
// of the lobe's prediction. Asserted within [1/2.5, 2].
TEST(GlintLifespan, Kemppinen2025HalvesWhereTheGlintLobePredicts) {
    const Material plane = makeBuiltinScene("plane90").materials.front();
    const double alpha = plane.alpha;
    const double microRoughness = materialParams(findGlintMethod("kemppinen2025"), plane, {}).at("micro_roughness");
    for (bool piD : {true, false}) {
        glm::dvec3 h0 = centreHalfVector(0.0);
        double d = kemppinen2025::smoothD(h0, glm::dvec2(alpha), kemppinen2025::kGgx) * (piD ? M_PI : 1.0);
        double sigma = microRoughness * std::sqrt(d);
        glm::dvec2 x0 = kemppinen2025::toPrior(h0, glm::dvec2(alpha), kemppinen2025::kGgx);
        double predicted = angleWhere(
            [&](double a) {
                return glm::length(kemppinen2025::toPrior(centreHalfVector(a), glm::dvec2(alpha), kemppinen2025::kGgx) - x0);
            },
            1.665 * sigma);
        std::vector<double> angles;
        for (int i = 1; i <= 8; ++i) angles.push_back(predicted * 0.35 * i);
        std::vector<std::string> sets = {std::string("kemppinen2025.angular_covariance=") + (piD ? "pi_d" : "d")};
        double measured = measuredHalfAngle("kemppinen2025", sets, angles);
        std::printf("kemppinen2025 angular_covariance=%s: correlation halves at %.5f rad (%.3f deg), predicted %.5f rad\n",
                    piD ? "pi_d" : "d", measured, measured * 180 / M_PI, predicted);
        EXPECT_GT(measured / predicted, 1 / 2.5) << (piD ? "pi_d" : "d");
        EXPECT_LT(measured / predicted, 2.0) << (piD ? "pi_d" : "d");
    }
}

// chermain2020: every glint is a Gaussian lobe of deviation sigma_lobe in the dictionary's slopes (Alg. 3), which
// are the material's slopes m = -h.xy / h.z whitened by the target's sigma = alpha / sqrt 2, warped radially for GGX
// (T, shaders/glints/chermain2020/chermain2020.glsl) and scaled by sigma_dict (the cells' rotation keeps distances).
// Like kemppinen2025's lobes, the correlation falls to 0.5 at a shift of 1.665 sigma_lobe / sigma_dict in T(W m).
// The prediction solves that at the image centre; measured 1.20 of it (the table is read linearly between texels
// 1.1 sigma_lobe apart, which widens a lobe); asserted within a factor 1.5 both ways. With the authors' density
// randomization and lobe clamp (the dictionary's lobe is what is predicted); with the material mapping's zeta 0
// and lobe_count=material it measured 1.54x (docs/chermain2020.md; not investigated further).
TEST(GlintLifespan, Chermain2020HalvesWhereTheDictionaryLobePredicts) {
    const Material plane = makeBuiltinScene("plane90").materials.front();
    ASSERT_EQ(plane.ndf, NdfType::Ggx);
    const double sigma = plane.alpha / std::sqrt(2.0), lobe = 0.02 / (0.5 / std::sqrt(2.0));
    auto warped = [&](double angle) {
        glm::dvec3 h = centreHalfVector(angle);
        glm::dvec2 u = -glm::dvec2(h.x, h.y) / (h.z * sigma);
        double r2 = glm::dot(u, u);
        return r2 > 1e-12 ? u * std::sqrt(2.0 * std::log(1.0 + 0.5 * r2) / r2) : u;
    };
    glm::dvec2 u0 = warped(0.0);
    double predicted = angleWhere([&](double a) { return glm::length(warped(a) - u0); }, 1.665 * lobe);
    std::vector<double> angles;
    for (int i = 1; i <= 8; ++i) angles.push_back(predicted * 0.35 * i);
    double measured = measuredHalfAngle(
        "chermain2020", {"chermain2020.density_randomization=2", "chermain2020.lobe_count=clamped"}, angles);
    std::printf("chermain2020: correlation halves at %.5f rad (%.3f deg), predicted %.5f rad\n", measured,
                measured * 180 / M_PI, predicted);
    EXPECT_GT(measured / predicted, 1 / 1.5);
    EXPECT_LT(measured / predicted, 1.5);
}

namespace {

struct FootprintRow {
    SparkleStats small, filtered;
};

// The smooth D of `scene` at `size`, rendered once per test process: every method's row divides by the same
// image (the render is deterministic, so a second render would give the same floats).
const std::vector<float>& smoothGlintD(const std::string& scene, int size) {
    static std::map<std::pair<std::string, int>, std::vector<float>> rendered;
    auto [it, inserted] = rendered.try_emplace({scene, size});
    if (inserted) it->second = renderGlintD(scene, "smooth", size);
    return it->second;
}

// D / D_smooth over the highlight at N pixels, and of the 4N render box-filtered 4x4 down to N (D and D_smooth
// filtered separately: a pixel of the small render sees the facets of its 4x4 block).
FootprintRow footprintRow(const std::string& scene, const std::string& method, int n,
                          const std::vector<std::string>& sets = {}) {
    FootprintRow row;
    row.small = sparkleStats(renderGlintD(scene, method, n, sets), smoothGlintD(scene, n));
    std::vector<float> big = renderGlintD(scene, method, 4 * n, sets);
    const std::vector<float>& bigSmooth = smoothGlintD(scene, 4 * n);
    row.filtered = sparkleStats(boxDownsample(big, 4 * n, 4 * n, 4), boxDownsample(bigSmooth, 4 * n, 4 * n, 4));
    std::printf("| %s | %s | %.3f / %.3f | %.4f / %.4f | %.2f | %.3f / %.3f |\n", method.c_str(), scene.c_str(),
                row.small.meanRatio, row.filtered.meanRatio, row.small.variance, row.filtered.variance,
                row.filtered.variance > 0 ? row.small.variance / row.filtered.variance : 0.0, row.small.zeroFraction,
                row.filtered.zeroFraction);
    return row;
}

}  // namespace

// Deliot & Belcour's central claim (Sec. 4, Fig. 4): correct counting statistics for any footprint. A pixel of a
// 64-pixel render is compared with the 4x4 block it covers in a 256-pixel render (D and D_smooth box-filtered),
// printed as the docs' table (docs/glint_statistics.md): mean (small / filtered), variance, ratio, zero fraction.
// Asserted for every method: the means agree within 5 % (deliot2023, zirr2016) / 10 % (kemppinen2025, wang2020,
// chermain2020);
// for deliot2023 the zero fractions agree within 0.03. The variances are reported, not asserted: neighbouring
// pixels of the large render share facets (deliot2023's grid cell is 1.5 px, interpolated over simplex vertices;
// zirr2016's cells are bilinear; kemppinen2025's filter is a Gaussian wider than a pixel), so a box of 16 of them
// is not 16 independent sub-footprints and keeps more variance than one pixel over the same area: measured ratios
// 0.2-0.5 (deliot2023, zirr2016), 0.09 (kemppinen2025). A variance test of the counting law needs disjoint
// footprints: Deliot2023Blending does that on controlled footprints.
TEST(GlintFootprint, SmallPixelsHaveTheStatisticsOfFilteredLargeOnes) {
    std::printf("| method | scene | mean small / filtered | variance small / filtered | ratio | zeros small / filtered |\n");
    std::printf("|---|---|---|---|---|---|\n");
    for (const char* scene : {"plane90", "plane25"}) {
        // At the authors' supplemental density and R (log_density 16, R 0.005), not the plane material's sparser
        // mapping (12.5, 0.0025): the small and the large render draw independent realizations (other LODs), and
        // at the material's density their means differ by counting noise alone by about 5 % (measured 0.943 on
        // plane90, 1.042 on plane25), more than the tolerance this test needs to catch a biased footprint.
        FootprintRow d = footprintRow(scene, "deliot2023", 64,
                                      {"deliot2023.log_density=16", "deliot2023.microfacet_roughness=0.005"});
        EXPECT_NEAR(d.small.meanRatio / d.filtered.meanRatio, 1.0, 0.05) << scene;
        EXPECT_NEAR(d.small.zeroFraction, d.filtered.zeroFraction, 0.03) << scene;
        FootprintRow z = footprintRow(scene, "zirr2016", 64);
        EXPECT_NEAR(z.small.meanRatio / z.filtered.meanRatio, 1.0, 0.05) << scene;
        for (const char* other : {"kemppinen2025", "wang2020", "chermain2020"}) {
            FootprintRow o = footprintRow(scene, other, 64);
            EXPECT_NEAR(o.small.meanRatio / o.filtered.meanRatio, 1.0, 0.10) << other << " " << scene;
        }
    }
}
