// Deliot & Belcour 2023 (shaders/glints/deliot2023*.glsl) through the real GL pipeline against CPU references
// (engine/glints/deliot2023_reference.h, engine/render/brdf_reference.h) and exact statistics.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "core/files.h"
#include "gl/program.h"
#include "glints/deliot2023_probe.h"
#include "glints/deliot2023_reference.h"
#include "glints/deliot2023_resources.h"
#include "platform/context.h"
#include "render/brdf_reference.h"
#include "render/offscreen.h"
#include "support/golden.h"

using namespace glimmer;
namespace dl = glimmer::deliot2023;

namespace {

struct BinomialStats {
    double N, p, mean, variance, pZero, probAtLeastOne;
};

// Runs shaders/glints/deliot2023_binomial_stats.comp: every (uniform, Gaussian) pair of the method's noise
// texture (512 x 512 x 4 = 1,048,576 samples) through deliotGatedBinomial, per (N, p).
std::vector<BinomialStats> shaderBinomialStats(const std::vector<glm::vec2>& configs) {
    gl::ProgramDesc desc;
    desc.name = "deliot2023_binomial_stats";
    desc.stages = {{GL_COMPUTE_SHADER, "glints/deliot2023_binomial_stats.comp"}};
    gl::Program program(defaultShaderDir(), desc);
    Deliot2023Resources resources;
    resources.bind();
    const int size = dl::kNoiseSize;
    gl::Buffer configBuffer = gl::createBuffer(GLsizeiptr(configs.size() * sizeof(glm::vec2)), configs.data(), 0);
    gl::Buffer sums = gl::createBuffer(GLsizeiptr(configs.size() * size * 4 * sizeof(double)), nullptr, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 14, configBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 15, sums.id());
    program.use();
    glDispatchCompute(size / 64, GLuint(configs.size()), 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<double> rows(configs.size() * size * 4);
    glGetNamedBufferSubData(sums.id(), 0, GLsizeiptr(rows.size() * sizeof(double)), rows.data());
    std::vector<BinomialStats> stats;
    const double samples = double(size) * size * 4;
    for (size_t c = 0; c < configs.size(); ++c) {
        double s1 = 0, s2 = 0, zeros = 0;
        for (int r = 0; r < size; ++r) {
            const double* row = &rows[(c * size + r) * 4];
            s1 += row[0];
            s2 += row[1];
            zeros += row[2];
        }
        double mean = s1 / samples;
        stats.push_back({configs[c].x, configs[c].y, mean, s2 / samples - mean * mean, zeros / samples,
                         rows[c * size * 4 + 3]});
    }
    return stats;
}

std::unique_ptr<GLContext> makeContext() { return createHeadlessContext(Backend::Egl); }

}  // namespace

// Sec. 6.3, Eq. 16-18: the gated Gaussian approximation against the exact binomial law b(N, p) over N in
// [0.5, 1e6] and p in [1e-7, 1], computed from the shader's own output. Tolerances (stated, not fitted per case):
//  - P(count = 0): the gate makes it exact by construction: |P0 - (1-p)^N| <= 5 sigma_stat + 1e-3 (half-float
//    quantization of the uniform numbers).
//  - mean: |mean - N p| <= 0.1 N p + 0.5 + 5 sigma_stat (the floor of Eq. 18 shifts the mean by up to half a count,
//    the Gaussian stand-in for b(N - 1, p) costs up to 10 % in the small-count regime).
//  - variance: |var - N p (1 - p)| <= 0.35 N p (1 - p) + 0.25 + stat (a discretized Gaussian is coarser than the
//    binomial at a few counts: e.g. N = 2, p = 0.5 gives 0.36 instead of 0.5).
// The same samples through the CPU mirror (deliot2023_reference.cpp) must agree with the shader to 1e-3 relative.
TEST(Deliot2023Binomial, GatedGaussianMatchesExactBinomialLaw) {
    auto context = makeContext();
    const std::vector<double> Ns = {0.5, 1, 2, 3, 5, 10, 30, 100, 1e3, 1e4, 1e5, 1e6};
    const std::vector<double> ps = {1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.05, 0.1, 0.3, 0.5, 0.9, 1.0};
    std::vector<glm::vec2> configs;
    for (double N : Ns)
        for (double p : ps) configs.emplace_back(float(N), float(p));
    std::vector<BinomialStats> stats = shaderBinomialStats(configs);

    // CPU mirror on the very same random numbers for a subset (the full set would take a while on the CPU).
    std::vector<uint32_t> texels = dl::makeNoiseTexels();
    const double samples = double(texels.size());
    for (const BinomialStats& s : stats) {
        dl::Moments exact = dl::exactBinomialMoments(s.N, s.p);
        double statMean = std::sqrt(std::max(exact.variance, 1e-12) / samples);
        double statP0 = std::sqrt(std::max(exact.pZero * (1 - exact.pZero), 1e-12) / samples);
        double statVar = exact.variance * std::sqrt(2.0 / samples) + 1e-6;
        std::string where = "N=" + std::to_string(s.N) + " p=" + std::to_string(s.p);
        EXPECT_NEAR(s.pZero, exact.pZero, 5 * statP0 + 1e-3) << where;
        EXPECT_NEAR(s.mean, exact.mean, 0.1 * exact.mean + 0.5 + 5 * statMean) << where;
        EXPECT_NEAR(s.variance, exact.variance, 0.35 * exact.variance + 0.25 + 5 * statVar) << where;
        // Eq. 16 in float must stay accurate where (1 - p)^N cancels (tiny p): relative error 1e-4.
        double exactP1 = s.N < 1 ? s.N * s.p : -std::expm1(s.N * std::log1p(-std::min(s.p, 1.0 - 1e-300)));
        if (s.N >= 1 && s.p >= 1.0) exactP1 = 1.0;
        EXPECT_NEAR(s.probAtLeastOne, exactP1, 1e-4 * exactP1) << where;
    }
    for (size_t c = 0; c < configs.size(); c += 7) {
        double sum = 0;
        for (uint32_t t : texels) {
            dl::NoisePair r = dl::unpackNoisePair(t);
            sum += dl::gatedBinomial(configs[c].x, configs[c].y, r.uniform, r.gaussian);
        }
        double cpuMean = sum / samples;
        EXPECT_NEAR(stats[c].mean, cpuMean, 1e-3 * cpuMean + 1e-6) << "shader vs CPU mirror, config " << c;
    }
}

// A law can look right in the moments and still be off in the shape: for a few mid-range cases compare the whole
// histogram with the exact binomial pmf (total variation distance <= 0.12, the coarseness of a discretized Gaussian).
TEST(Deliot2023Binomial, HistogramCloseToBinomialPmf) {
    std::vector<uint32_t> texels = dl::makeNoiseTexels();
    for (auto [N, p] : std::vector<std::pair<int, double>>{{4, 0.3}, {20, 0.1}, {50, 0.5}, {200, 0.02}}) {
        std::vector<double> histogram(N + 1, 0.0);
        for (uint32_t t : texels) {
            dl::NoisePair r = dl::unpackNoisePair(t);
            int k = int(dl::gatedBinomial(float(N), float(p), r.uniform, r.gaussian));
            ASSERT_GE(k, 0);
            ASSERT_LE(k, N);
            histogram[k] += 1.0 / texels.size();
        }
        double tv = 0.0, logPmf0 = N * std::log1p(-p);
        for (int k = 0; k <= N; ++k) {
            double logPmf = std::lgamma(N + 1.0) - std::lgamma(k + 1.0) - std::lgamma(N - k + 1.0) + k * std::log(p) +
                            (N - k) * std::log1p(-p);
            tv += 0.5 * std::abs(histogram[k] - std::exp(logPmf));
        }
        (void)logPmf0;
        EXPECT_LT(tv, 0.12) << "N=" << N << " p=" << p;
    }
}
