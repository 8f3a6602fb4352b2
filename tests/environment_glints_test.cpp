// Environment glints (Kneiphof & Klein 2025; engine/environment/environment_glints.h, glints/deliot2023/deliot2023_multinomial.glsl):
// - the hierarchical multinomial on the method's own noise: each level's mean count is n p_i (within the statistics
//   and the clamping's bias), the counts always sum to n, for K = 4 and 8, small and large n;
// - the radiance levels span the environment's luminance above the black level (log-spaced), and the unfiltered
//   weights of every texel give back its luminance (sum_i w_i L_i = Y);
// - a glinty plane under the sky alone: the mean of its environment glints equals the split sum within 5 % for 4 and
//   8 levels, the glints are there (bright outliers), and at high density every pixel converges to the split sum;
// - wang2020 draws its own environment glints by default (its IBL mode), an explicit --ibl keeps precedence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/files.h"
#include "environment/environment_glints.h"
#include "glints/deliot2023/deliot2023_noise.h"
#include "glints/deliot2023/deliot2023_resources.h"
#include "glints/methods.h"
#include "platform/context.h"
#include "environment/environment.h"
#include "offscreen/offscreen.h"
#include "support/test_needs.h"

// What this suite needs beyond the CPU (its ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(EnvironmentGlints, GlContext);

namespace glimmer {
namespace {

struct MultinomialStats {
    std::vector<double> mean;   // per level
    double worstConservation = 0.0, draws = 0.0;
};

MultinomialStats multinomialStats(float n, int levels, const std::vector<float>& p) {
    gl::ProgramDesc desc;
    desc.name = "deliot2023_multinomial_stats";
    desc.stages = {{GL_COMPUTE_SHADER, "glints/deliot2023/deliot2023_multinomial_stats.comp"}};
    gl::Program program(defaultShaderDir(), desc);
    Deliot2023Resources resources;
    resources.bind();
    struct Config {
        glm::vec4 nLevels;
        glm::vec4 p[2];
    } config{{n, float(levels), 0.0f, 0.0f}, {}};
    for (int i = 0; i < 8; ++i) config.p[i / 4][i % 4] = i < int(p.size()) ? p[size_t(i)] : 0.0f;
    const int size = deliot2023::kNoiseSize;
    gl::Buffer configBuffer = gl::createBuffer(sizeof(Config), &config, 0);
    gl::Buffer sums = gl::createBuffer(GLsizeiptr(size_t(size) * 10 * sizeof(double)), nullptr, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 14, configBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 15, sums.id());
    program.use();
    glDispatchCompute(size / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<double> rows(size_t(size) * 10);
    glGetNamedBufferSubData(sums.id(), 0, GLsizeiptr(rows.size() * sizeof(double)), rows.data());
    MultinomialStats stats;
    stats.mean.assign(8, 0.0);
    stats.draws = double(size) * (size / 7);
    for (int r = 0; r < size; ++r) {
        for (int i = 0; i < 8; ++i) stats.mean[size_t(i)] += rows[size_t(r) * 10 + size_t(i)];
        stats.worstConservation = std::max(stats.worstConservation, rows[size_t(r) * 10 + 8]);
    }
    for (double& m : stats.mean) m /= stats.draws;
    return stats;
}

TEST(EnvironmentGlints, MultinomialIsUnbiasedAndConservesTheCount) {
    auto context = createHeadlessContext(Backend::Egl);
    struct Case {
        float n;
        int levels;
        std::vector<float> p;
    };
    const Case cases[] = {
        {0.7f, 4, {0.9f, 0.05f, 0.03f, 0.02f}},
        {1.5f, 4, {0.5f, 0.2f, 0.2f, 0.1f}},
        {12.0f, 4, {0.97f, 0.01f, 0.015f, 0.005f}},
        {400.0f, 4, {0.6f, 0.1f, 0.1f, 0.2f}},
        {5000.0f, 8, {0.99f, 0.001f, 0.002f, 0.001f, 0.003f, 0.001f, 0.001f, 0.001f}},
        {40.0f, 8, {0.3f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f, 0.1f}},
    };
    for (const Case& c : cases) {
        MultinomialStats stats = multinomialStats(c.n, c.levels, c.p);
        EXPECT_LT(stats.worstConservation, 1e-3 * c.n) << "n " << c.n;
        for (int i = 0; i < c.levels; ++i) {
            double expected = c.n * c.p[size_t(i)];
            // Statistics: sd of a count ~ sqrt(n p (1 - p)), of the mean over the draws / sqrt(draws); the Gaussian's
            // clamp to [1, n - 1] moves the mean by a little for small n p (a few % of n p).
            double sigma = std::sqrt(std::max(expected * (1.0 - c.p[size_t(i)]), 1e-9) / stats.draws);
            double tolerance = 6.0 * sigma + 0.03 * expected + 1e-4;
            std::printf("n %7.1f K %d level %d: mean count %.5f, n p %.5f\n", c.n, c.levels, i, stats.mean[size_t(i)], expected);
            EXPECT_NEAR(stats.mean[size_t(i)], expected, tolerance) << "n " << c.n << " level " << i;
        }
    }
}

RenderRequest skyPlane(const std::string& method, int levels, float logDensity) {
    RenderRequest request;
    request.scene = "plane25";   // a 25-degree plane: the sky fills the reflected lobe
    request.width = request.height = 96;
    request.settings.method = method;
    request.settings.ibl = "prefiltered";
    request.settings.apply("light.intensity=0");   // the sky alone (the procedural sky keeps its sun disk then)
    request.settings.apply("material.glinty=1");
    request.settings.apply("material.alpha=0.25");
    request.settings.apply("ao.enabled=0");
    request.settings.apply(std::string("ibl.glint_levels=") + (levels == 8 ? "8" : levels == 4 ? "4" : "off"));
    if (method == "deliot2023") request.settings.apply("deliot2023.log_density=" + std::to_string(logDensity));
    return request;
}

double channelMean(const RenderResult& r) {
    double sum = 0.0;
    for (size_t i = 0; i < r.hdr.size(); i += 4) sum += r.hdr[i] + r.hdr[i + 1] + r.hdr[i + 2];
    return sum / double(r.hdr.size() / 4);
}

// Kneiphof & Klein 2025: the attenuation's expectation is 1, so over the plane the environment glints average to the
// split sum; at high density each pixel is the split sum.
TEST(EnvironmentGlints, MeanUnderTheSkyMatchesTheSplitSum) {
    RenderRequest base = skyPlane("deliot2023", 0, 8.0f);
    OffscreenSession session(base);
    const RenderResult reference = session.render(base);
    const double smooth = channelMean(reference);
    for (int levels : {4, 8}) {
        RenderResult r = session.render(skyPlane("deliot2023", levels, 8.0f));
        double mean = channelMean(r);
        std::vector<float> values;
        for (size_t i = 0; i < r.hdr.size(); i += 4) values.push_back(r.hdr[i] + r.hdr[i + 1] + r.hdr[i + 2]);
        std::sort(values.begin(), values.end());
        double p999 = values[size_t(0.999 * double(values.size() - 1))];
        std::printf("environment glints, %d levels: mean / split sum = %.4f, p99.9 / mean = %.2f\n", levels,
                    mean / smooth, p999 / mean);
        EXPECT_NEAR(mean / smooth, 1.0, 0.05) << levels << " levels";
        EXPECT_GT(p999 / mean, 1.5) << "no glints with " << levels << " levels";
    }
    RenderResult dense = session.render(skyPlane("deliot2023", 4, 40.0f));
    double worst = 0.0;
    for (size_t i = 0; i < dense.hdr.size(); i += 4)
        worst = std::max(worst, std::abs(double(dense.hdr[i]) - reference.hdr[i]) / (reference.hdr[i] + 0.01));
    std::printf("at log density 40: worst |glinty - split sum| / (split sum + 0.01) = %.4f\n", worst);
    EXPECT_LT(worst, 0.02);
}

size_t differingValues(const RenderResult& a, const RenderResult& b) {
    size_t n = 0;
    for (size_t i = 0; i < a.hdr.size(); ++i) n += a.hdr[i] != b.hdr[i];
    return n;
}

// The window's first picture defers the environment glints (Renderer::RefinementPace::Deferred): that frame is the
// image without them, bit for bit; the frames after it, paced one refinement a frame, build them, and once built a
// deferring frame keeps them.
TEST(EnvironmentGlints, FirstPictureDefersThemAndTheNextFrameBuildsThem) {
    const RenderRequest glinty = skyPlane("deliot2023", 4, 8.0f);
    OffscreenSession window(glinty);
    window.renderer().setRefinementPace(Renderer::RefinementPace::Deferred);
    const RenderResult first = window.render(glinty);
    const RenderResult without = window.render(skyPlane("deliot2023", 0, 8.0f));
    window.renderer().setRefinementPace(Renderer::RefinementPace::OnePerFrame);
    RenderResult second = window.render(glinty);   // the probes' capture (a refinement too) may come first
    for (int frame = 0; frame < 2 && !window.renderer().waitingRefinements().empty(); ++frame)
        second = window.render(glinty);
    EXPECT_TRUE(window.renderer().waitingRefinements().empty());
    window.renderer().setRefinementPace(Renderer::RefinementPace::Deferred);
    const RenderResult third = window.render(glinty);
    EXPECT_EQ(differingValues(first, without), 0u) << "the deferred first picture has environment glints";
    EXPECT_GT(differingValues(second, without), without.hdr.size() / 8) << "the next frame built none";
    EXPECT_EQ(differingValues(third, second), 0u) << "built glints dropped by a later deferring frame";
}

// The window's strip names the on-demand work of the last edit (Renderer::lastEditPasses): the environment glints
// built by the frame after the first picture are listed until an edit begins; an edit that needs no on-demand work
// then lists nothing, not that earlier build.
TEST(EnvironmentGlints, AnEditForgetsTheEarlierOnDemandPasses) {
    const RenderRequest glinty = skyPlane("deliot2023", 4, 8.0f);
    OffscreenSession window(glinty);
    window.render(glinty);
    bool listed = false;
    for (const PassTiming& t : window.renderer().lastEditPasses()) listed |= t.name == "env_glints.levels";
    EXPECT_TRUE(listed) << "the build is not listed";
    window.renderer().forgetEditPasses();
    window.render(glinty);   // nothing to rebuild
    EXPECT_TRUE(window.renderer().lastEditPasses().empty());
}

TEST(EnvironmentGlints, Wang2020DrawsItsOwnEnvironmentGlintsByDefault) {
    EXPECT_EQ(defaultIblOf(findGlintMethod("wang2020")), "wang2020");
    EXPECT_EQ(defaultIblOf(findGlintMethod("deliot2023")), "prefiltered");
    EXPECT_EQ(defaultIblOf(findGlintMethod("kemppinen2025")), "prefiltered");
    EXPECT_TRUE(findGlintMethod("deliot2023").environmentGlints);
}

}  // namespace
}  // namespace glimmer
