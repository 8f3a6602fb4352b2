// The Zirr & Kaplanyan 2016 baseline (shaders/glints/zirr2016/zirr2016.glsl) through the real GL pipeline against its CPU
// reference (engine/glints/zirr2016_reference.h). Its LOD-lerp variance loss is tested beside Deliot & Belcour's
// distributed blending in tests/deliot2023_test.cpp (Deliot2023Blending).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "reference/method_probe.h"
#include "reference/zirr2016_reference.h"
#include "platform/context.h"
#include "render/aov.h"
#include "offscreen/offscreen.h"
#include "scene/builtin_scenes.h"
#include "support/golden.h"

using namespace glimmer;
namespace zk = glimmer::zirr2016;

namespace {

std::vector<GlintProbeInput> randomProbes(int count, uint32_t seed, float maxLogRatio) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<GlintProbeInput> inputs;
    for (int i = 0; i < count; ++i) {
        GlintProbeInput in;
        float phi = unit(rng) * 6.2831853f, major = std::exp2(-11.0f + 4.0f * unit(rng));
        float ratio = std::exp2(maxLogRatio * unit(rng));
        glm::vec2 a(std::cos(phi), std::sin(phi)), b(-a.y, a.x);
        in.uv = glm::vec2(unit(rng), unit(rng)) * 20.0f + 1.0f;
        in.duvdx = a * major;
        in.duvdy = b * (major / ratio);
        in.h = glm::normalize(glm::vec3((unit(rng) - 0.5f) * 0.3f, (unit(rng) - 0.5f) * 0.3f, 1.0f));
        in.ndf = i % 2;
        inputs.push_back(in);
    }
    return inputs;
}

RenderResult renderWith(const std::string& scene, const std::string& method, const std::vector<std::string>& sets,
                        const std::string& aov = "final") {
    RenderRequest request;
    request.scene = scene;
    request.environment = "none";   // glints respond to the lights; the environment would add a smooth term only
    request.width = request.height = 256;
    request.settings.method = method;
    for (const std::string& s : sets) request.settings.apply(s);
    request.settings.debugView = findAov(aov).viewId;
    return renderOffscreen(request);
}

double imageMean(const RenderResult& r) {
    double sum = 0;
    for (size_t i = 0; i < r.hdr.size(); i += 4) sum += (r.hdr[i] + r.hdr[i + 1] + r.hdr[i + 2]) / 3.0;
    return sum / (r.hdr.size() / 4);
}

}  // namespace

// The shader's glintD equals the CPU reference (same seeds and hashes, same float formulas) pixel by pixel on random
// footprints and half vectors. Float transcendental differences may flip a floor() or a cdf comparison: at least
// 97 % of the probes agree to 1e-3 relative, and the means over all probes agree to 1 %.
TEST(Zirr2016, ShaderMatchesCpuReference) {
    auto context = createHeadlessContext(Backend::Egl);
    zk::Params params;
    params.logDensity = 18.0f;
    params.searchCone = 0.03f;   // wider than the default so that most probes see a non-zero count
    GlintMethodProbe probe("zirr2016", {{"log_density", params.logDensity}, {"search_cone", params.searchCone}});
    std::vector<GlintProbeInput> inputs = randomProbes(3000, 3, 6.0f);
    std::vector<GlintProbeOutput> out = probe.run(inputs);
    size_t agree = 0, nonZero = 0;
    double gpuSum = 0, cpuSum = 0;
    for (size_t i = 0; i < inputs.size(); ++i) {
        const GlintProbeInput& in = inputs[i];
        float cpu = zk::glintD(in.uv, in.duvdx, in.duvdy, glm::normalize(in.h), in.alpha, in.ndf, params);
        agree += std::abs(out[i].D - cpu) <= 1e-3f * std::max({cpu, out[i].D, out[i].smoothD});
        nonZero += cpu > 0.0f;
        gpuSum += out[i].D;
        cpuSum += cpu;
    }
    EXPECT_GE(double(agree) / inputs.size(), 0.97);
    EXPECT_GE(double(nonZero) / inputs.size(), 0.3) << "too few glinting probes for the comparison to mean much";
    EXPECT_NEAR(gpuSum / cpuSum, 1.0, 0.01);
}

// Footprint coverage (the authors' shader): the axis-aligned box of the +-0.5 px parallelogram, ceil(long / short)
// steps along its long side up to the cap of 16; beyond it the LOD rises so 16 steps cover the long side
// (isotropic growth: the stretched glints of D&B Fig. 11). The cost (binomial draws per light = 2 levels x steps x
// 4 cells of the bilinear lookup) therefore varies with the footprint, unlike Deliot & Belcour's constant 48.
TEST(Zirr2016, AnisotropyCapAndVaryingCost) {
    auto context = createHeadlessContext(Backend::Egl);
    GlintMethodProbe probe("zirr2016", {});
    std::vector<GlintProbeInput> inputs = randomProbes(2000, 9, 8.0f);
    std::vector<GlintProbeOutput> out = probe.run(inputs);
    float minCost = 1e9f, maxCost = 0.0f;
    for (size_t i = 0; i < inputs.size(); ++i) {
        zk::Footprint fp = zk::footprint(inputs[i].uv, inputs[i].duvdx, inputs[i].duvdy);
        EXPECT_NEAR(out[i].footprint.x / fp.ratio, 1.0, 1e-4) << i;
        EXPECT_NEAR(out[i].footprint.y, fp.lod, 1e-4) << i;
        int steps = int(out[i].footprint.z);
        EXPECT_EQ(steps, fp.steps) << i;
        glm::vec2 extent = glm::abs(inputs[i].duvdx) + glm::abs(inputs[i].duvdy);
        float longSide = std::max(extent.x, extent.y), shortSide = std::min(extent.x, extent.y);
        EXPECT_EQ(steps, std::clamp(int(std::ceil(longSide / shortSide - 1e-4f)), 1, 16)) << i;
        if (fp.ratio > 16.5f) {
            EXPECT_NEAR(out[i].footprint.y, std::log2(longSide / 16), 1e-3) << "capped LOD " << i;
            EXPECT_EQ(out[i].footprint.w, 1.0f);
        }
        EXPECT_NEAR(out[i].footprint.y, std::log2(std::max(shortSide, longSide / 16)), 1e-3) << "LOD " << i;
        EXPECT_EQ(out[i].extra.x, 8.0f * steps) << i;
        minCost = std::min(minCost, out[i].extra.x);
        maxCost = std::max(maxCost, out[i].extra.x);
    }
    EXPECT_LE(minCost, 16.0f);
    EXPECT_EQ(maxCost, 128.0f);
}

// The inverse-CDF binomial of one uniform against the exact law: over a uniform grid of u, the mean, the variance
// and P(0) of b(N, p) for N = 0.5 .. 1e6 and N p up to 1e4. Tolerances: mean 1 % + 0.02 (the Gaussian branch
// rounds, so it keeps the mean; A&S 26.2.23 errs by 4.5e-4), variance 15 % + 0.3 (a rounded Gaussian at N p just
// above 5), P(0) 2e-3 (exact in the pmf branch; the Gaussian's tail below 0.5 at N p = 10 is 8e-4).
TEST(Zirr2016, InverseCdfBinomialMatchesExactLaw) {
    const int grid = 20000;
    for (double N : {0.5, 1.0, 3.0, 10.0, 100.0, 1e4, 1e6})
        for (double p : {1e-5, 1e-3, 0.01, 0.1, 0.5}) {
            if (N * p > 1e4) continue;
            double s1 = 0, s2 = 0, zeros = 0;
            for (int i = 0; i < grid; ++i) {
                float k = zk::binomial(float(N), float(p), (float(i) + 0.5f) / grid);
                s1 += k;
                s2 += double(k) * k;
                zeros += k == 0.0f;
            }
            double mean = s1 / grid, variance = s2 / grid - mean * mean;
            double exactMean = N < 1 ? N * p : N * p;
            double exactVar = N < 1 ? N * p * (1 - N * p) : N * p * (1 - p);
            double exactP0 = N < 1 ? 1 - N * p : std::exp(N * std::log1p(-p));
            std::string where = "N=" + std::to_string(N) + " p=" + std::to_string(p);
            EXPECT_NEAR(mean, exactMean, 0.01 * exactMean + 0.02) << where;
            EXPECT_NEAR(variance, exactVar, 0.15 * exactVar + 0.3) << where;
            EXPECT_NEAR(zeros / grid, exactP0, 2e-3) << where;
        }
}

// The baseline also converges to the smooth NDF at very high density (image mean within 2 %) and preserves the
// mean at a glinty density (5 %).
TEST(Zirr2016, ConvergesToSmoothAndPreservesMean) {
    for (const char* scene : {"plane90", "plane25"})
        for (const char* ndf : {"ggx", "beckmann"}) {
            std::string n = std::string("material.ndf=") + ndf;
            double smooth = imageMean(renderWith(scene, "smooth", {n}));
            double dense = imageMean(renderWith(scene, "zirr2016", {n, "zirr2016.log_density=40"}));
            EXPECT_NEAR(dense / smooth, 1.0, 0.02) << scene << " " << ndf;
        }
    // Sparse (a few hundred facets light the highlight): one realization's mean is off by its counting noise
    // (measured 0.99-1.19 of smooth across search cones at log_density 11), so the mean is taken over four
    // independent realizations (each cone draws other angular cells), whose average must keep smooth's within 5 %.
    double smooth = imageMean(renderWith("plane90", "smooth", {}));
    double glinty = 0;
    for (const char* cone : {"0.01", "0.015", "0.02", "0.03"})
        glinty += imageMean(renderWith("plane90", "zirr2016",
                                       {"zirr2016.log_density=11", std::string("zirr2016.search_cone=") + cone})) / 4;
    EXPECT_NEAR(glinty / smooth, 1.0, 0.05);
}

class Zirr2016Golden : public ::testing::TestWithParam<std::string> {};

TEST_P(Zirr2016Golden, MatchesReference) {
    RenderResult result = renderWith(GetParam(), "zirr2016", {});
    EXPECT_EQ(result.stats["counts"]["non_finite_values"].get<size_t>(), 0u);
    test::GoldenComparison comparison =
        test::compareWithGolden("zirr2016_" + GetParam(), result.display, result.width, result.height);
    EXPECT_TRUE(comparison.passed) << comparison.message;
}

INSTANTIATE_TEST_SUITE_P(AllScenes, Zirr2016Golden, ::testing::ValuesIn(builtinSceneNames()));
