// Wang, Deng & Holzschuch 2020 (shaders/glints/wang2020/wang2020.glsl, engine/glints/wang2020_*): DPF tables against the
// definition, the quadtree's multinomial splitting, the three-scale glint pass through the real GL pipeline against
// the explicit-particle CPU reference, material editing and bad input.
// Tests use DPF tables at half the paper's resolution (45 x 45 x 90, wang2020.table_scale=2), cached under the
// build directory; the paper's 90 x 90 x 180 is the default of the method.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>

#include "core/error.h"
#include "core/files.h"
#include "core/image_io.h"
#include "environment/environment.h"
#include "glints/methods.h"
#include "glints/wang2020/wang2020_dpf.h"
#include "glints/wang2020/wang2020_post_pass.h"
#include "glints/wang2020/wang2020_prefilter.h"
#include "glints/wang2020/wang2020_quadtree.h"
#include "glints/wang2020/wang2020_resources.h"
#include "offscreen/offscreen.h"
#include "platform/context.h"
#include "reference/environment_reference.h"
#include "reference/wang2020_post_reference.h"
#include "reference/wang2020_reference.h"
#include "render/aov.h"
#include "support/golden.h"
#include "support/measure.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(Wang2020Quadtree, GlContext);
GLIMMER_SUITE_NEEDS(Wang2020Render, GlContext);
GLIMMER_SUITE_NEEDS(Wang2020Editing, GlContext);
GLIMMER_SUITE_NEEDS(Wang2020BadInput, Process);
GLIMMER_SUITE_NEEDS(Wang2020Prefilter, GlContext);
GLIMMER_SUITE_NEEDS(Wang2020Environment, GlContext);
GLIMMER_SUITE_NEEDS(Wang2020Golden, GlContext);
GLIMMER_SUITE_NEEDS(Wang2020PostPass, GlContext);

using namespace glimmer;
namespace w = glimmer::wang2020;

namespace {

// GLIMMER_ASSETS_DIR, else <source>/../shared/assets, else /work/shared/assets (tests skip what is missing).
std::string assetsDir() {
    if (const char* d = std::getenv("GLIMMER_ASSETS_DIR"); d && *d) return d;
    std::string near = std::string(GLIMMER_SOURCE_DIR) + "/../shared/assets";
    return std::filesystem::exists(near) ? near : "/work/shared/assets";
}

const std::string kScene = std::string(GLIMMER_TEST_DIR) + "/data/wang2020_point.json";

void useTestCache() { setenv("GLIMMER_DPF_CACHE", GLIMMER_TEST_OUTPUT_DIR "/wang2020_dpf_cache", 0); }

const w::DpfSet& testDpfSet() {
    useTestCache();
    static const w::DpfSet set = w::loadOrGenerateDpfSet({45, 45, 90}, w::defaultDpfCacheDir());
    return set;
}

// Monte Carlo version of the DPF's definition (Eq. 6): the fraction of particles, normals drawn from the Beckmann
// D(m)(m.n), whose mirror reflection of wi falls in the cone of half-angle gamma around wo.
double countedDpf(glm::vec3 wi, glm::vec3 wo, float alpha, float gamma, int particles, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int hits = 0;
    float cosGamma = std::cos(gamma);
    for (int k = 0; k < particles; ++k) {
        float tan2 = -alpha * alpha * std::log(1.0f - u(rng));
        float c = 1.0f / std::sqrt(1.0f + tan2), s = std::sqrt(1.0f - c * c), phi = 2.0f * w::kPi * u(rng);
        glm::vec3 m(s * std::cos(phi), s * std::sin(phi), c);
        float im = glm::dot(wi, m);
        if (im > 0.0f && glm::dot(2.0f * im * m - wi, wo) >= cosGamma) ++hits;
    }
    return double(hits) / particles;
}

}  // namespace

// The DPF (quadrature of the reflection density over the cone) equals counting explicit Beckmann particles
// (Eq. 6) at gamma = 1 degree; tolerance 4 binomial standard deviations + 3 %.
TEST(Wang2020Dpf, QuadratureMatchesParticleCounting) {
    struct Case {
        float alpha, thetaI, thetaO, phi;
    };
    for (Case c :
         {Case{0.1f, 20, 25, 170}, Case{0.1f, 40, 38, 175}, Case{0.5f, 30, 10, 120}, Case{0.02f, 10, 10, 180}}) {
        glm::vec3 wi = w::sphericalDirection(c.thetaI * w::kDegree, 0.0f);
        glm::vec3 wo = w::sphericalDirection(c.thetaO * w::kDegree, c.phi * w::kDegree);
        double quad = w::dpfByQuadrature(wi, wo, c.alpha, w::kBaseGamma, 4);
        int n = 4000000;
        double counted = countedDpf(wi, wo, c.alpha, w::kBaseGamma, n, 7);
        double sigma = std::sqrt(quad * (1 - quad) / n);
        EXPECT_NEAR(counted, quad, 4 * sigma + 0.03 * quad) << c.alpha << " " << c.thetaI << " " << c.thetaO;
        EXPECT_GT(counted, 0.0);
    }
}

// Extraction + accumulation: the table for gamma = 6 degrees, built from the 1-degree tables, matches the
// definition counted directly with explicit particles at gamma = 6 degrees (within 8 %: table interpolation);
// extraction at a sampled roughness returns that sample's table exactly.
TEST(Wang2020Dpf, AccumulationMatchesCountingAtGamma) {
    const w::DpfSet& set = testDpfSet();
    EXPECT_EQ(set.tables.size(), w::kRoughnessSamples.size());
    w::DpfTable base = w::extractDpf(set, 0.1f);
    EXPECT_EQ(base.values, set.tables[2].values);
    w::DpfTable acc = w::accumulateDpf(base, 6.0f * w::kDegree);
    for (auto [ti, to, phi] : {std::tuple{20.f, 25.f, 170.f}, {35.f, 30.f, 160.f}, {10.f, 12.f, 100.f}}) {
        glm::vec3 wi = w::sphericalDirection(ti * w::kDegree, 0.0f),
                  wo = w::sphericalDirection(to * w::kDegree, phi * w::kDegree);
        double counted = countedDpf(wi, wo, 0.1f, 6.0f * w::kDegree, 1000000, 11);
        EXPECT_NEAR(acc.lookup(wi, wo), counted, 0.08 * counted + 1e-3) << ti << " " << to << " " << phi;
    }
    EXPECT_THROW(w::extractDpf(set, 0.01f), UsageError);
}

// Multinomial splitting: every level sums to N, children sum to their parent, the same seed gives the same tree
// whatever the thread count, and leaf counts have the multinomial's mean and variance (N/L, N/L (1 - 1/L)).
TEST(Wang2020Quadtree, MultinomialSplitting) {
    const double n = 1e6;
    w::Quadtree a = w::buildQuadtree(n, 9, 5, 1), b = w::buildQuadtree(n, 9, 5, 2);
    EXPECT_EQ(a.counts, b.counts);
    for (int level = 0; level <= 9; ++level) {
        double sum = 0;
        for (int y = 0; y < (1 << level); ++y)
            for (int x = 0; x < (1 << level); ++x) {
                sum += a.count(level, x, y);
                if (level < 9) {
                    uint32_t children = a.count(level + 1, 2 * x, 2 * y) + a.count(level + 1, 2 * x + 1, 2 * y) +
                                        a.count(level + 1, 2 * x, 2 * y + 1) + a.count(level + 1, 2 * x + 1, 2 * y + 1);
                    ASSERT_EQ(children, a.count(level, x, y));
                }
            }
        EXPECT_EQ(sum, n) << level;
    }
    double leaves = std::ldexp(1.0, 18), mean = n / leaves, var = 0;
    for (int y = 0; y < 512; ++y)
        for (int x = 0; x < 512; ++x) var += std::pow(a.count(9, x, y) - mean, 2);
    var /= leaves;
    EXPECT_NEAR(var / (mean * (1 - 1 / leaves)), 1.0, 0.02);
    EXPECT_EQ(a.bytes(), w::Quadtree::levelOffset(10) * 4);
    EXPECT_NE(w::buildQuadtree(n, 9, 6, 2).counts, a.counts);
    EXPECT_THROW(w::buildQuadtree(n, 20, 1), UsageError);
}

namespace {

struct WangTestMaterial {
    float alpha, gamma, particles;
};

// A 256x256 view of tests/data/wang2020_point.json with the method wang2020 for material m (tables at 45x45x90),
// plus `extraSets`.
RenderRequest wangRequest(const WangTestMaterial& m, const std::string& camera, const std::vector<std::string>& extraSets) {
    RenderRequest request;
    request.scene = kScene;
    request.camera = camera;
    request.width = request.height = 256;
    request.settings.method = "wang2020";
    std::vector<std::string> sets = {"material.alpha=" + std::to_string(m.alpha),
                                     "wang2020.roughness=" + std::to_string(m.alpha),
                                     "wang2020.gamma=" + std::to_string(m.gamma),
                                     "wang2020.particles=" + std::to_string(m.particles), "wang2020.table_scale=2"};
    sets.insert(sets.end(), extraSets.begin(), extraSets.end());
    for (const std::string& s : sets) request.settings.apply(s);
    return request;
}

// The same view lit by environment `env` through --ibl wang2020 only (lights off).
RenderRequest wangEnvironmentRequest(const WangTestMaterial& m, const std::string& camera, const std::string& env,
                                     std::vector<std::string> extraSets = {}) {
    extraSets.push_back("light.intensity=0");
    RenderRequest request = wangRequest(m, camera, extraSets);
    request.environment = env;
    request.settings.ibl = "wang2020";
    return request;
}

std::vector<float> renderAov(OffscreenSession& session, const RenderRequest& request, const char* aov) {
    RenderRequest r = request;
    r.settings.debugView = findAov(aov).viewId;
    return session.render(r).hdr;
}

// The pixel footprint read back from the G-buffer AOVs (uv, duv/dx, duv/dy) of pixel p.
w::Footprint footprintAt(const std::vector<float>& uv, const std::vector<float>& dx, const std::vector<float>& dy,
                         size_t p) {
    return {glm::dvec2(uv[4 * p], uv[4 * p + 1]), glm::dvec2(dx[4 * p], dx[4 * p + 1]),
            glm::dvec2(dy[4 * p], dy[4 * p + 1])};
}

// The explicit-particle reference's environment glint at a footprint of the plane y = 0 (UV = (x, z); shading
// frame t = +x, b = +z, n = +y), seen from `eye`, times Schlick's F with f0 = 0.9 as the shader applies it.
// worldRadiance(direction) is the environment's radiance along a world direction.
template <class WorldRadiance>
glm::vec3 explicitEnvironmentGlint(const w::Quadtree& tree, const w::Footprint& fp, glm::vec3 eye, float alpha,
                                   WorldRadiance worldRadiance) {
    glm::vec3 toEye = glm::normalize(eye - glm::vec3(float(fp.center.x), 0.0f, float(fp.center.y)));
    glm::vec3 wo(toEye.x, toEye.z, toEye.y);
    glm::vec3 L = w::explicitParticleEnvironment(
        tree, fp, wo, alpha, [&](glm::vec3 wi) { return worldRadiance(glm::vec3(wi.x, wi.z, wi.y)); });
    return L * (0.9f + 0.1f * float(std::pow(1.0 - wo.z, 5.0)));
}

// Per pixel of a 256x256 view of tests/data/wang2020_point.json: the shader's D (--aov glint), the explicit
// reference's D on the same footprint (uv, duv/dx, duv/dy read back from the G-buffer AOVs), the expected
// particle count and the radiance weight I / (d^2 4 cos_o) that turns D into the glint's radiance (F G aside,
// equal for both).
struct PixelPair {
    double gpu, ref, expected, weight;
};

// One OffscreenSession; each seed re-runs only the quadtree pass (the particles change, the tables do not).
// With several variants (sets of --set values that change the shader's scales, not the G-buffer), each seed renders
// the footprints and computes the explicit reference once, and the glint AOV once per variant: the reference, not
// the render, is most of the time. Returns the pixel pairs of each variant, in the order given.
std::vector<std::vector<PixelPair>> renderPairsPerVariant(const WangTestMaterial& m, const std::string& camera,
                                                          int seeds, const std::vector<std::vector<std::string>>& variants) {
    useTestCache();
    RenderRequest request = wangRequest(m, camera, variants.front());
    OffscreenSession session(request);
    std::vector<std::vector<PixelPair>> pairs(variants.size());
    for (int seed = 1; seed <= seeds; ++seed) {
        request.settings.apply("wang2020.seed=" + std::to_string(seed));
        auto aov = [&](const char* name) { return renderAov(session, request, name); };
        std::vector<float> uv = aov("uv"), dx = aov("duvdx"), dy = aov("duvdy");
        std::vector<std::vector<float>> glints;
        for (const std::vector<std::string>& variant : variants) {
            for (const std::string& set : variant) request.settings.apply(set);
            glints.push_back(aov("glint"));
        }
        const Scene& scene = session.scene();
        glm::vec3 eye{};
        for (const Camera& c : scene.cameras)
            if (c.name == camera) eye = c.position;
        glm::vec3 light = scene.lights.at(0).vector;
        float intensity = scene.lights.at(0).intensity;
        float depth = 11;
        w::Quadtree tree = w::buildQuadtree(m.particles, int(depth), uint32_t(seed));
        for (size_t p = 0; p < uv.size() / 4; ++p) {
            glm::vec2 u(uv[4 * p], uv[4 * p + 1]);
            w::Footprint fp = footprintAt(uv, dx, dy, p);
            glm::vec3 pos(u.x, 0.0f, u.y);  // plane y = 0, UV = (x, z); shading frame t = +x, b = +z, n = +y
            glm::vec3 toEye = glm::normalize(eye - pos), toLight = light - pos;
            float d2 = glm::dot(toLight, toLight);
            toLight = glm::normalize(toLight);
            glm::vec3 wo(toEye.x, toEye.z, toEye.y), wi(toLight.x, toLight.z, toLight.y);
            w::ReferenceResult ref = w::explicitParticleD(tree, fp, wi, wo, m.alpha, m.gamma * w::kDegree);
            for (size_t v = 0; v < variants.size(); ++v)
                pairs[v].push_back({glints[v][4 * p], ref.D, m.particles * fp.area(), intensity / (d2 * 4.0 * wo.z)});
        }
    }
    return pairs;
}

std::vector<PixelPair> renderPairs(const WangTestMaterial& m, const std::string& camera, int seeds = 1,
                                   const std::vector<std::string>& extraSets = {}) {
    return renderPairsPerVariant(m, camera, seeds, {extraSets}).front();
}

// Writes shader | reference side by side (glint radiance D x weight, scaled so the reference's 99th percentile
// maps to white, sRGB-ish gamma) under the test output directory, for docs and eyeballing.
void writeSideBySide(const std::vector<PixelPair>& pairs, const std::string& name) {
    std::vector<double> refs;
    for (size_t i = 0; i < 256 * 256; ++i) refs.push_back(pairs[i].ref * pairs[i].weight);
    std::vector<double> sorted = refs;
    std::sort(sorted.begin(), sorted.end());
    double scale = 1.0 / std::max(sorted[size_t(sorted.size() * 0.99)], 1e-12);
    std::vector<uint8_t> rgba(512 * 256 * 4, 255);
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            const PixelPair& p = pairs[size_t(y) * 256 + x];
            for (int side = 0; side < 2; ++side) {
                double v = std::pow(std::clamp((side ? p.ref : p.gpu) * p.weight * scale, 0.0, 1.0), 1.0 / 2.2);
                uint8_t c = uint8_t(std::lround(v * 255));
                size_t o = (size_t(y) * 512 + x + side * 256) * 4;
                rgba[o] = rgba[o + 1] = rgba[o + 2] = c;
            }
        }
    std::filesystem::create_directories(GLIMMER_TEST_OUTPUT_DIR);
    writePng(std::filesystem::path(GLIMMER_TEST_OUTPUT_DIR) / (name + ".png"), rgba.data(), 512, 256);
}

}  // namespace

// Paper Table 1: average glint energy, total energy / glint count N, of the shader within 25 % of the explicit
// particle reference for the paper's two materials under a point light (256x256, top view). N being equal, this
// compares the total glint energy. The second material is sparse (about 1.5 particles per pixel: micro-scale),
// the first dense (about 15: meso-scale). The sparse one
// averages 8 particle sets (seeds) to reach several hundred glints (one set: ratios 1.07-1.18 seen).
TEST(Wang2020Render, AverageGlintEnergyMatchesExplicitReference) {
    for (WangTestMaterial m : {WangTestMaterial{0.1f, 6.0f, 1e6f}, WangTestMaterial{0.5f, 2.0f, 1e5f}}) {
        int seeds = m.particles < 1e6f ? 8 : 1;
        std::vector<PixelPair> pairs = renderPairs(m, "top", seeds);
        double gpu = 0, ref = 0;
        int gpuGlints = 0, refGlints = 0;
        for (const PixelPair& p : pairs) {
            gpu += p.gpu * p.weight;
            ref += p.ref * p.weight;
            gpuGlints += p.gpu > 0;
            refGlints += p.ref > 0;
        }
        std::printf(
            "wang2020 alpha %.2f gamma %.0f N %.0e: average energy shader %.4g reference %.4g (ratio %.3f); "
            "glinting pixels %d / %d\n",
            m.alpha, m.gamma, m.particles, gpu / m.particles / seeds, ref / m.particles / seeds, gpu / ref, gpuGlints,
            refGlints);
        char name[64];
        std::snprintf(name, sizeof name, "wang2020_point_a%.1f_shader_vs_reference", m.alpha);
        writeSideBySide(pairs, name);
        EXPECT_GT(refGlints, 200);
        EXPECT_NEAR(gpu / ref, 1.0, 0.25) << m.alpha;
    }
}

// The shader's node words (wang2020::shaderNodeWords) against the tree: a node with one particle names a leaf of
// that node holding one particle; an inner node with a child mask has its count and exactly its non-empty children.
TEST(Wang2020ShaderTree, WordsLeadToTheParticles) {
    w::Quadtree tree = w::buildQuadtree(3e4, 9, 3, 1);
    std::vector<uint32_t> words = w::shaderNodeWords(tree);
    ASSERT_EQ(words.size(), tree.counts.size());
    size_t singles = 0, masked = 0;
    for (int level = 0; level <= tree.depth; ++level)
        for (int y = 0; y < (1 << level); ++y)
            for (int x = 0; x < (1 << level); ++x) {
                uint32_t count = tree.count(level, x, y);
                uint32_t word = words[w::Quadtree::levelOffset(level) + (size_t(y) << level) + size_t(x)];
                if (count == 1) {
                    ASSERT_NE(word & w::kSingleParticle, 0u) << level;
                    int shift = tree.depth - level, rx = int(word & 0x1FFFu), ry = int((word >> 13) & 0x1FFFu);
                    ASSERT_LT(std::max(rx, ry), 1 << shift) << level;
                    ASSERT_EQ(tree.count(tree.depth, (x << shift) + rx, (y << shift) + ry), 1u) << level;
                    ++singles;
                } else if (level < tree.depth && count > 0) {
                    ASSERT_EQ(word & ~0x3FFFFFFu, w::kChildMask | (word & 0x3C000000u)) << level;
                    EXPECT_EQ(word & 0x3FFFFFFu, count);
                    for (int c = 0; c < 4; ++c)
                        EXPECT_EQ((word >> (26 + c)) & 1u,
                                  tree.count(level + 1, 2 * x + (c & 1), 2 * y + (c >> 1)) > 0 ? 1u : 0u);
                    ++masked;
                } else {
                    EXPECT_EQ(word, count);
                }
            }
    EXPECT_GT(singles, 10000u);
    EXPECT_GT(masked, 10000u);
}

// Sec. 4.3's traversal finds exactly the particles in each pixel's footprint: the count the shader found (--aov
// footprint, z) equals the CPU traversal's (wang2020::forEachParticle, the explicit reference's) on the footprint
// read back from the G-buffer AOVs, on the tilted view whose footprints run from micro to meso (one material, so
// the meso nodes wholly inside add their exact count). Also the cost the node words buy (measured: mean nodes
// visited per pixel 25.6 micro, 86 meso; the plain-count tree needed 67 and 162): at most 40 and 130.
TEST(Wang2020Render, TraversalFindsTheParticlesOfTheFootprint) {
    useTestCache();
    const float particles = 2.5e5f;
    RenderRequest request = wangRequest(WangTestMaterial{0.4f, 4.0f, particles}, "tilted", {"wang2020.transition=0"});
    OffscreenSession session(request);
    std::vector<float> uv = renderAov(session, request, "uv"), dx = renderAov(session, request, "duvdx"),
                       dy = renderAov(session, request, "duvdy"), found = renderAov(session, request, "footprint");
    w::Quadtree tree = w::buildQuadtree(particles, 11, 1);
    size_t pixels[2] = {0, 0}, mismatched = 0;
    double visits[2] = {0, 0};
    for (size_t p = 0; p < uv.size() / 4; ++p) {
        int scale = int(found[4 * p + 1]);
        if (found[4 * p] <= 0.0f || (scale != 0 && scale != 1)) continue;
        size_t inside = 0;
        w::forEachParticle(tree, footprintAt(uv, dx, dy, p), 0.4f, [&](const w::Particle&) { ++inside; });
        ++pixels[scale];
        visits[scale] += found[4 * p + 3];
        if (double(inside) != double(found[4 * p + 2])) ++mismatched;
    }
    std::printf("wang2020 traversal: %zu micro, %zu meso pixels; mean nodes visited %.1f, %.1f; %zu counts differ\n",
                pixels[0], pixels[1], visits[0] / double(pixels[0]), visits[1] / double(pixels[1]), mismatched);
    ASSERT_GT(pixels[0], 5000u);
    ASSERT_GT(pixels[1], 5000u);
    EXPECT_LE(double(mismatched), 1e-3 * double(pixels[0] + pixels[1]));   // float vs double at the edge
    EXPECT_LE(visits[0] / double(pixels[0]), 40.0);
    EXPECT_LE(visits[1] / double(pixels[1]), 130.0);
}

// Sec. 4.3: the three scales agree where they meet. On the tilted view the expected particle count per footprint
// grows with distance and crosses the thresholds (4 and 64); in the bands [t/2, t) and [t, 2t) around each
// threshold t the shader's glint energy is within 25 % of the explicit reference's (which has no scales), on
// either side; with the paper's hard thresholds (transition 0) and with our default one-octave blend. Roughness
// 0.4 is one of the DPF samples, so the roughness interpolation of the DPF extraction (measured: 0.82-0.88 of the
// reference's energy in these bands at alpha 0.3) does not mix in.
// The reference has no scales, so both transitions are compared with one reference (renderPairsPerVariant).
TEST(Wang2020Render, ScalesAgreeAtThresholds) {
    const std::vector<std::string> transitions = {"wang2020.transition=0", "wang2020.transition=1"};
    // N chosen per threshold so that the threshold's row lies inside the highlight of the tilted view.
    for (auto [threshold, particles] : {std::pair{4.0, 2.5e5f}, std::pair{64.0, 3.4e6f}}) {
        std::vector<std::vector<PixelPair>> perTransition = renderPairsPerVariant(
            WangTestMaterial{0.4f, 4.0f, particles}, "tilted", threshold < 10 ? 2 : 1, {{transitions[0]}, {transitions[1]}});
        for (size_t t = 0; t < transitions.size(); ++t) {
            const char* transition = transitions[t].c_str();
            const std::vector<PixelPair>& pairs = perTransition[t];
            for (auto [lo, hi] : {std::pair{threshold / 2, threshold}, std::pair{threshold, threshold * 2}}) {
                double gpu = 0, ref = 0;
                int pixels = 0;
                for (const PixelPair& p : pairs)
                    if (p.expected >= lo && p.expected < hi) {
                        gpu += p.gpu * p.weight;
                        ref += p.ref * p.weight;
                        ++pixels;
                    }
                std::printf("wang2020 %s N %.2g, expected count [%g, %g): %d pixels, shader / reference energy %.3f\n",
                            transition, particles, lo, hi, pixels, gpu / ref);
                EXPECT_GT(pixels, 5000) << lo;
                EXPECT_NEAR(gpu / ref, 1.0, 0.25) << transition << " band [" << lo << ", " << hi << ")";
            }
        }
    }
}

// Sec. 4.5 material editing: N (and the seed) re-run only the quadtree; roughness or gamma only the DPF
// extraction + accumulation; parameters that need no new data (the scale thresholds) nothing.
TEST(Wang2020Editing, OnlyNeededPassesRun) {
    useTestCache();
    auto context = createHeadlessContext(Backend::Egl);
    Wang2020Resources resources;
    auto names = [](const std::vector<std::pair<std::string, double>>& ran) {
        std::vector<std::string> n;
        for (const auto& r : ran) n.push_back(r.first);
        return n;
    };
    using V = std::vector<std::string>;
    ParamValues values{{"table_scale", 2}, {"depth", 8}};
    EXPECT_EQ(names(resources.update(values)),
              (V{"wang2020.dpf_generation", "wang2020.dpf_accumulation", "wang2020.quadtree"}));
    EXPECT_EQ(names(resources.update(values)), V{});
    values["particles"] = 5e5;
    EXPECT_EQ(names(resources.update(values)), V{"wang2020.quadtree"});
    values["gamma"] = 3;
    EXPECT_EQ(names(resources.update(values)), V{"wang2020.dpf_accumulation"});
    values["roughness"] = 0.3f;
    EXPECT_EQ(names(resources.update(values)), V{"wang2020.dpf_accumulation"});
    values["micro_max"] = 8;
    values["macro_min"] = 100;
    EXPECT_EQ(names(resources.update(values)), V{});
}

// Bad input: out-of-range gamma, N, roughness or depth are one-line usage errors naming the key.
TEST(Wang2020BadInput, OutOfRangeParameters) {
    for (const char* bad : {"wang2020.gamma=20", "wang2020.gamma=0.5", "wang2020.particles=0",
                            "wang2020.roughness=0.01", "wang2020.depth=14"}) {
        RenderSettings settings;
        settings.method = "wang2020";
        try {
            settings.apply(bad);
            ADD_FAILURE() << bad << " accepted";
        } catch (const UsageError& e) {
            std::string key = std::string(bad).substr(0, std::string(bad).find('='));
            EXPECT_NE(std::string(e.what()).find(key.substr(key.find('.') + 1)), std::string::npos) << e.what();
        }
    }
}

// The environment prefilter pass (Eq. 16-17) on the GPU equals its CPU version for a constant environment of
// radiance 1 (where the table must not depend on the normal): every entry within 2 % (float, texture filtering),
// for both estimators of Eq. 16; the Table 2 resolutions.
TEST(Wang2020Prefilter, MatchesCpuForConstantEnvironment) {
    useTestCache();
    auto context = createHeadlessContext(Backend::Egl);
    EXPECT_EQ(w::prefilterResolution(0.1f).size(), size_t(31 * 60 * 10 * 36));
    EXPECT_EQ(w::prefilterResolution(0.5f).size(), size_t(10 * 18 * 4 * 12));
    Environment environment(defaultShaderDir());
    environment.update("constant:1,1,1", SunDescription{}, "--env");
    environment.bind(1.0f, 0.0f);
    Wang2020Resources resources;
    float alpha = 0.4f, gamma = 3.0f;
    resources.update({{"table_scale", 2}, {"depth", 6}, {"roughness", alpha}, {"gamma", gamma}});
    w::Prefilter prefilter(defaultShaderDir());
    w::PrefilterResolution res = w::prefilterResolution(alpha);
    w::DpfTable dpf = w::accumulateDpf(w::extractDpf(testDpfSet(), alpha), gamma * w::kDegree);
    for (auto estimator : {w::Prefilter::Estimator::Cone, w::Prefilter::Estimator::Dpf}) {
        double ms = prefilter.run(resources.dpfTexture(), alpha, gamma * w::kDegree, estimator, res);
        std::printf("wang2020 prefilter %dx%dx%dx%d (estimator %d): %.1f ms\n", res.thetaN, res.phiN, res.thetaO,
                    res.phiO, int(estimator), ms);
        std::vector<glm::vec4> table = prefilter.read();
        for (int to = 0; to < res.thetaO; ++to)
            for (int po = 0; po < res.phiO; ++po) {
                float thetaO = (to + 0.5f) / res.thetaO * 0.5f * w::kPi, phiO = float(po) / res.phiO * 2 * w::kPi;
                glm::vec2 cpu = w::prefilteredConstantEnvironment(dpf, alpha, gamma * w::kDegree,
                                                                  w::sphericalDirection(thetaO, phiO),
                                                                  w::PrefilterEstimator(int(estimator)));
                EXPECT_GT(cpu.x, 0.0f);
                for (int tn = 0; tn < res.thetaN; tn += 3)
                    for (int pn = 0; pn < res.phiN; pn += 5) {
                        glm::vec4 gpu = table[((size_t(tn) * res.phiN + pn) * res.thetaO + to) * res.phiO + po];
                        ASSERT_NEAR(gpu.x, cpu.x, 0.02f * cpu.x + 1e-6f) << tn << " " << pn << " " << to << " " << po;
                        ASSERT_NEAR(gpu.w, cpu.y, 0.02f * cpu.y + 1e-7f) << tn << " " << pn << " " << to << " " << po;
                    }
            }
    }
}

// Eq. 16's integral for a constant map, L^o(o) = int P(i, o, gamma) M(i, o) di, by quadrature over the hemisphere of i
// (400 x 800 cells, P from the accumulated table), against the two K = 64 estimators of the prefilter, alpha 0.1 and
// 0.4, gamma 6, view angles 30-85.5 degrees: the cone form (the default) within 2 % up to 76.5 degrees and 7 % at
// 85.5 (measured 0.986-1.002, and 0.993 / 0.938 at 85.5), and its worst ratio closer to one than the paper's
// literal form's worst (measured 0.870 at 76.5 and 0.662 at 85.5 degrees for alpha 0.1).
TEST(Wang2020Prefilter, ConeEstimatorMatchesQuadratureAtGrazingAngles) {
    float gamma = 6.0f * w::kDegree;
    double worstCone = 0.0, worstLiteral = 0.0;
    for (float alpha : {0.1f, 0.4f}) {
        w::DpfTable dpf = w::accumulateDpf(w::extractDpf(testDpfSet(), alpha), gamma);
        for (float degrees : {30.0f, 60.0f, 76.5f, 85.5f}) {
            glm::vec3 wo = w::sphericalDirection(degrees * w::kDegree, 0.7f);
            double quadrature = 0.0;
            const int rows = 400, columns = 800;
            for (int a = 0; a < rows; ++a)
                for (int b = 0; b < columns; ++b) {
                    double cosI = (a + 0.5) / rows, sinI = std::sqrt(1.0 - cosI * cosI), phi = (b + 0.5) / columns * 2 * w::kPi;
                    glm::vec3 wi(float(sinI * std::cos(phi)), float(sinI * std::sin(phi)), float(cosI));
                    glm::vec3 h = glm::normalize(wi + wo);
                    float M = glm::dot(wi, h) * w::smithG1Beckmann(wi, alpha) * w::smithG1Beckmann(wo, alpha) / (h.z * wo.z);
                    quadrature += std::min(dpf.lookup(wi, wo), 1.0f) * M * (1.0 / rows) * (2 * w::kPi / columns);
                }
            double cone = w::prefilteredConstantEnvironment(dpf, alpha, gamma, wo, w::PrefilterEstimator::Cone).x;
            double literal = w::prefilteredConstantEnvironment(dpf, alpha, gamma, wo, w::PrefilterEstimator::Dpf).x;
            std::printf("wang2020 Eq. 16, alpha %.1f, theta_o %.1f: quadrature %.4f, cone K=64 %.4f (%.3f), dpf K=64 %.4f "
                        "(%.3f)\n", alpha, degrees, quadrature, cone, cone / quadrature, literal, literal / quadrature);
            EXPECT_NEAR(cone / quadrature, 1.0, degrees > 80.0f ? 0.07 : 0.02) << alpha << " " << degrees;
            worstCone = std::max(worstCone, std::abs(cone / quadrature - 1.0));
            worstLiteral = std::max(worstLiteral, std::abs(literal / quadrature - 1.0));
        }
    }
    EXPECT_LT(worstCone, worstLiteral);
}

// Environment path (--ibl wang2020, Sec. 4.2, Eq. 16-20) against the explicit-particle Monte Carlo reference
// (wang2020::explicitParticleEnvironment: every particle in the footprint reflects the environment around
// reflect(o, m_k)), under a constant white environment and under an HDR map, for the paper's two materials; lights
// off, metallic plane (no diffuse). Average glint energy (total / N) within 25 %. The HDR map is the studio
// (soft boxes): with a small sun (rooitou_park) the sparse material measured 0.70, with the warehouse 0.82: K = 64
// deterministic importance samples per table entry (Eq. 16) miss small bright sources, and the reference itself is
// noisy there (a few particles see the sun).
// CI: both materials under the constant environment and the sparse one (the hard case) under the map; the dense
// material under the map (its session prefilters a 31x60x10x36 table, about 7 s, then the reference) is in CI
// through SnowAndGlitterClothNextToReference (same material and map, tilted view); GLIMMER_MEASURE=1 adds it here.
TEST(Wang2020Environment, AverageGlintEnergyMatchesExplicitReference) {
    if (!test::fullMeasurement()) GTEST_SKIP() << "GLIMMER_MEASURE=1 runs it (25 s); CI: SnowAndGlitterClothNextToReference, Wang2020Render.AverageGlintEnergyMatchesExplicitReference";
    useTestCache();
    std::string hdr = assetsDir() + "/hdri/studio_small_03_1k.hdr";
    std::vector<std::string> envs = {"constant:1,1,1"};
    if (std::filesystem::exists(hdr)) envs.push_back(hdr);
    for (const std::string& env : envs)
        for (WangTestMaterial m : {WangTestMaterial{0.1f, 6.0f, 1e6f}, WangTestMaterial{0.5f, 2.0f, 1e5f}}) {
            if (env == hdr && m.particles >= 1e6f && !test::fullMeasurement()) continue;
            RenderRequest request = wangEnvironmentRequest(m, "top", env);
            int seeds = m.particles < 1e6f ? 4 : 1;
            OffscreenSession session(request);
            ImageF image;
            bool constant = env.rfind("constant", 0) == 0;
            if (!constant) image = readImage(env);
            glm::vec3 eye = session.scene().cameras.at(0).position;
            double gpu = 0, ref = 0;
            for (int seed = 1; seed <= seeds; ++seed) {
                request.settings.apply("wang2020.seed=" + std::to_string(seed));
                auto aov = [&](const char* name) { return renderAov(session, request, name); };
                std::vector<float> uv = aov("uv"), dx = aov("duvdx"), dy = aov("duvdy"), final = aov("final");
                w::Quadtree tree = w::buildQuadtree(m.particles, 11, uint32_t(seed));
                for (size_t p = 0; p < uv.size() / 4; ++p) {
                    glm::vec3 L = explicitEnvironmentGlint(tree, footprintAt(uv, dx, dy, p), eye, m.alpha,
                                                           [&](glm::vec3 world) {
                        return constant ? glm::vec3(1.0f) : envref::sampleEquirect(image, world);
                    });
                    ref += (L.x + L.y + L.z) / 3.0;
                    gpu += (final[4 * p] + final[4 * p + 1] + final[4 * p + 2]) / 3.0;
                }
            }
            std::printf("wang2020 environment %s alpha %.1f: average energy shader %.4g reference %.4g (ratio %.3f)\n",
                        constant ? "constant" : "hdr", m.alpha, gpu / m.particles / seeds, ref / m.particles / seeds,
                        gpu / ref);
            EXPECT_NEAR(gpu / ref, 1.0, 0.25) << env << " " << m.alpha;
        }
}

// Bad input through the command line: out-of-range gamma or N, a missing environment map, the IBL mode without its
// glint method: a one-line error naming the culprit and a non-zero exit, no crash.
TEST(Wang2020BadInput, CommandLine) {
    std::string out = std::string(GLIMMER_TEST_OUTPUT_DIR) + "/wang2020_bad.png";
    struct Case {
        std::vector<std::string> args;
        std::string expect;
    };
    for (const Case& c : std::vector<Case>{
             {{"--method", "wang2020", "--set", "wang2020.gamma=30"}, "wang2020.gamma"},
             {{"--method", "wang2020", "--set", "wang2020.particles=-5"}, "wang2020.particles"},
             {{"--method", "wang2020", "--ibl", "wang2020", "--env", "/nonexistent/sky.hdr"}, "/nonexistent/sky.hdr"},
             {{"--method", "smooth", "--ibl", "wang2020"}, "--method wang2020"}}) {
        std::vector<std::string> args = {"render", "--scene", "plane90", "--size", "32x32", "--out", out};
        args.insert(args.end(), c.args.begin(), c.args.end());
        glimmer::test::ProcessResult r = glimmer::test::runGlimmer(args);
        EXPECT_NE(r.exitCode, 0) << c.expect;
        EXPECT_EQ(r.signal, 0) << c.expect;
        EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
        EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
}

// Sec. 4.5 through the renderer: with the environment path on, N edits re-run only the quadtree, gamma edits the
// DPF accumulation and the environment prefilter, colour and blur sizes nothing, the prefilter's estimator only the
// prefilter (passes listed in the render's stats).
TEST(Wang2020Editing, RendererRunsOnlyNeededPasses) {
    useTestCache();
    RenderRequest request;
    request.scene = kScene;
    request.width = request.height = 32;
    request.environment = "constant:1,1,1";
    request.settings.method = "wang2020";
    request.settings.ibl = "wang2020";
    for (const char* s : {"wang2020.table_scale=2", "wang2020.roughness=0.5", "material.alpha=0.5", "wang2020.depth=8"})
        request.settings.apply(s);
    OffscreenSession session(request);
    auto passes = [&](const std::string& set) {
        if (!set.empty()) request.settings.apply(set);
        std::vector<std::string> names;
        RenderResult result = session.render(request);
        for (const auto& p : result.stats["passes"])
            if (p["name"].get<std::string>().rfind("wang2020.", 0) == 0) names.push_back(p["name"]);
        return names;
    };
    using V = std::vector<std::string>;
    EXPECT_EQ(passes(""),
              (V{"wang2020.dpf_generation", "wang2020.dpf_accumulation", "wang2020.quadtree", "wang2020.prefilter"}));
    EXPECT_EQ(passes(""), V{});
    EXPECT_EQ(passes("wang2020.particles=3e5"), V{"wang2020.quadtree"});
    EXPECT_EQ(passes("wang2020.gamma=4"), (V{"wang2020.dpf_accumulation", "wang2020.prefilter"}));
    EXPECT_EQ(passes("wang2020.color_g=0.5"), V{});
    EXPECT_EQ(passes("ibl.prefilter=cone"), V{"wang2020.prefilter"});   // the Eq. 16 estimator: prefilter only
    EXPECT_EQ(passes("wang2020.blur_glints=5"), V{});                   // post-pass sizes: nothing to rebuild
}

// Golden images of the tilted view whose footprints cross the micro/meso threshold (N 2.5e5) and the meso/macro
// threshold (N 3.4e6) inside the highlight (tables at 45x45x90). The mean radiance agrees across the thresholds
// (ScalesAgreeAtThresholds); the texture does not: micro pixels show few bright glints, meso pixels a dense grain,
// macro pixels a smooth sheen (visible in these images; see docs/wang2020.md).
TEST(Wang2020Golden, TiltedViewAcrossThresholds) {
    useTestCache();
    for (const char* particles : {"2.5e5", "3.4e6"}) {
        RenderRequest request = wangRequest(WangTestMaterial{0.4f, 4.0f, std::stof(particles)}, "tilted", {"exposure=-1"});
        RenderResult result = renderOffscreen(request);
        EXPECT_EQ(result.stats["counts"]["non_finite_values"].get<size_t>(), 0u);
        test::GoldenComparison comparison = test::compareWithGolden(std::string("wang2020_tilted_n") + particles,
                                                                    result.display, result.width, result.height);
        EXPECT_TRUE(comparison.passed) << comparison.message;
    }
}

// Sec. 4.4 directional occlusion on a plane that cannot occlude itself: plane25 under the procedural sky alone
// (light.intensity 0, glinty, alpha 0.25). Every glinty pixel's mirror direction is visible (its target's alpha
// 1), and every row keeps at least half the smooth method's radiance. The screen-space march read the depth of the
// nearest texel, which at the far, grazing rows lies more than its 1 cm bias in front of the ray point: those
// rows were all occluded and rendered black.
TEST(Wang2020PostPass, APlaneDoesNotOccludeItsOwnReflection) {
    useTestCache();
    RenderRequest request;
    request.scene = "plane25";
    request.width = request.height = 128;
    request.environment = "procedural";
    request.settings.apply("light.intensity=0");
    request.settings.apply("material.alpha=0.25");
    request.settings.method = "smooth";
    OffscreenSession session(request);
    const RenderResult smooth = session.render(request);
    RenderRequest wang = request;
    wang.settings.method = "wang2020";
    wang.settings.ibl = "wang2020";
    const RenderResult glints = session.render(wang);
    const std::vector<float> environment = session.renderer().readMethodTarget(0);
    ASSERT_EQ(environment.size(), glints.hdr.size());
    size_t glinty = 0, occluded = 0;
    for (size_t p = 0; p < environment.size(); p += 4) {
        if (glints.hdr[p + 3] <= 0.0f) continue;   // sky
        ++glinty;
        occluded += environment[p + 3] < 0.5f;
    }
    EXPECT_GT(glinty, environment.size() / 4 / 2);
    EXPECT_EQ(occluded, 0u) << "of " << glinty << " plane pixels";
    double worstRow = 1e9;
    for (int y = 0; y < glints.height; ++y) {
        double a = 0.0, b = 0.0;
        for (int x = 0; x < glints.width; ++x) {
            const size_t i = (size_t(y) * glints.width + x) * 4;
            a += glints.hdr[i] + glints.hdr[i + 1] + glints.hdr[i + 2];
            b += smooth.hdr[i] + smooth.hdr[i + 1] + smooth.hdr[i + 2];
        }
        if (b > 0.0) worstRow = std::min(worstRow, a / b);
    }
    std::printf("plane25 under the sky: %zu of %zu pixels occluded, darkest row at %.3f of smooth\n", occluded, glinty,
                worstRow);
    EXPECT_GT(worstRow, 0.5);
}

// Sec. 4.4 "Gaussian Blurring" through the real pipeline: the 9-tap occlusion blur and the 3-tap glint blur of the
// post pass equal the CPU reference (glintpost::referencePostPass) applied to the lighting pass's glint targets,
// pixel by pixel. heightmap25 under the constant environment with its light on: the bumps occlude the mirror
// direction of part of the surface (both visibilities occur) and both glint targets are non-zero. The render with
// both blurs at 1 tap gives the radiance without glints (HDR minus occluded glints); adding the reference's blurred
// glints to it must give the render with the paper's blurs. Tolerance 1e-4 relative + 1e-5 absolute (float sums
// in another order).
TEST(Wang2020PostPass, BlursMatchCpuReference) {
    useTestCache();
    RenderRequest request;
    request.scene = "heightmap25";
    request.width = request.height = 128;
    request.environment = "constant:1,1,1";
    request.settings.method = "wang2020";
    request.settings.ibl = "wang2020";
    for (const char* s : {"wang2020.table_scale=2", "wang2020.roughness=0.2", "material.alpha=0.2",
                          "wang2020.particles=2e5", "wang2020.depth=9"})
        request.settings.apply(s);
    OffscreenSession session(request);
    auto render = [&](int occlusionTaps, int glintTaps) {
        RenderRequest r = request;
        r.settings.apply("wang2020.blur_occlusion=" + std::to_string(occlusionTaps));
        r.settings.apply("wang2020.blur_glints=" + std::to_string(glintTaps));
        return session.render(r).hdr;
    };
    std::vector<float> raw = render(1, 1);
    std::vector<float> blurred = render(9, 3);
    std::vector<float> environment = session.renderer().readMethodTarget(0);
    std::vector<float> lights = session.renderer().readMethodTarget(1);
    ASSERT_EQ(environment.size(), raw.size());

    size_t glinty = 0, occluded = 0;
    double environmentGlint = 0, lightGlint = 0;
    for (size_t p = 0; p < raw.size(); p += 4) {
        if (lights[p + 3] == 0.0f) continue;
        ++glinty;
        occluded += environment[p + 3] < 0.5f;
        environmentGlint += environment[p] + environment[p + 1] + environment[p + 2];
        lightGlint += lights[p] + lights[p + 1] + lights[p + 2];
    }
    std::printf("post pass: %zu glinty pixels, %zu occluded along the mirror direction; glint sums env %.4g lights %.4g\n",
                glinty, occluded, environmentGlint, lightGlint);
    ASSERT_GT(glinty, raw.size() / 4 / 2);
    EXPECT_GT(occluded, glinty / 100) << "no occlusion: the occlusion blur would not be tested";
    EXPECT_LT(occluded, glinty / 2);
    EXPECT_GT(environmentGlint, 0.0);
    EXPECT_GT(lightGlint, 0.0);

    std::vector<float> none = glintpost::referencePostPass(environment, lights, 128, 128, 1, 1);
    std::vector<float> paper = glintpost::referencePostPass(environment, lights, 128, 128, 9, 3);
    double worst = 0.0, changed = 0.0;
    for (size_t p = 0; p < raw.size(); p += 4)
        for (size_t c = 0; c < 3; ++c) {
            double expected = double(raw[p + c]) - none[p + c] + paper[p + c];
            double error = std::abs(blurred[p + c] - expected) / (1e-5 + 1e-4 * std::abs(expected));
            worst = std::max(worst, error);
            changed = std::max(changed, std::abs(double(blurred[p + c]) - raw[p + c]));
        }
    EXPECT_LE(worst, 1.0) << "largest error in units of the tolerance";
    EXPECT_GT(changed, 1e-2) << "the blurs changed nothing";
}

// The kernel weights: binomial rows (paper sizes 9 and 3), normalised, symmetric use; too wide a kernel is an error.
TEST(Wang2020PostPass, BinomialWeights) {
    std::vector<float> three = glintpost::binomialWeights(glintpost::radiusOf(3));
    ASSERT_EQ(three.size(), 2u);
    EXPECT_FLOAT_EQ(three[0], 0.5f);
    EXPECT_FLOAT_EQ(three[1], 0.25f);
    std::vector<float> nine = glintpost::binomialWeights(glintpost::radiusOf(9));
    ASSERT_EQ(nine.size(), 5u);
    const float row8[5] = {70, 56, 28, 8, 1};
    for (int k = 0; k < 5; ++k) EXPECT_FLOAT_EQ(nine[size_t(k)], row8[k] / 256.0f);
    EXPECT_EQ(glintpost::radiusOf(4), 1);
    EXPECT_EQ(glintpost::binomialWeights(0), std::vector<float>{1.0f});
    EXPECT_THROW(glintpost::binomialWeights(glintpost::kMaxRadius + 1), Error);
}

namespace {
// Texture along the expected particle count E on the tilted view (final radiance, blurs on): pixels of the central
// columns binned by log2 E in quarter octaves; per bin the coefficient of variation of the radiance (std / mean,
// the "texture": large for sparse glints, small for a sheen). Returns the largest |ln(CV ratio)| between
// neighbouring bins within [E_lo, E_hi): a hard change of texture at a scale threshold shows as one large step.
double largestTextureStep(const std::string& particles, const std::string& transition, double eLo, double eHi) {
    useTestCache();
    RenderRequest request =
        wangRequest(WangTestMaterial{0.4f, 4.0f, std::stof(particles)}, "tilted", {"wang2020.transition=" + transition});
    OffscreenSession session(request);
    std::vector<float> radiance = session.render(request).hdr;
    std::vector<float> expected = renderAov(session, request, "footprint");
    const int bins = int(std::round(4 * std::log2(eHi / eLo)));
    std::vector<double> sum(size_t(bins), 0.0), sum2(size_t(bins), 0.0), count(size_t(bins), 0.0);
    for (int y = 0; y < 256; ++y)
        for (int x = 96; x < 160; ++x) {
            size_t p = (size_t(y) * 256 + size_t(x)) * 4;
            double e = expected[p];
            if (e < eLo || e >= eHi) continue;
            int b = std::min(bins - 1, int(4 * std::log2(e / eLo)));
            double l = (radiance[p] + radiance[p + 1] + radiance[p + 2]) / 3.0;
            sum[size_t(b)] += l, sum2[size_t(b)] += l * l, count[size_t(b)] += 1;
        }
    double largest = 0.0, previous = -1.0;
    std::printf("wang2020 texture (CV) by quarter octave of E from %g, N %s, transition %s:", eLo, particles.c_str(),
                transition.c_str());
    for (int b = 0; b < bins; ++b) {
        if (count[size_t(b)] < 100) continue;
        double mean = sum[size_t(b)] / count[size_t(b)];
        double cv = std::sqrt(std::max(sum2[size_t(b)] / count[size_t(b)] - mean * mean, 0.0)) / std::max(mean, 1e-12);
        std::printf(" %.2f", cv);
        if (previous > 0.0) largest = std::max(largest, std::abs(std::log(cv / previous)));
        previous = cv;
    }
    std::printf("; largest step %.2f\n", largest);
    return largest;
}
}  // namespace

// "No visible seam" (Sec. 4.3) as a measurement: with the paper's hard thresholds the texture (CV of the radiance)
// jumps at the micro/meso threshold; with the default one-octave transition band the largest step between
// neighbouring quarter-octave bins of E stays below ln 2 (measured 0.62 at the micro/meso threshold, 0.15 at
// meso/macro), at both thresholds. The hard switch at micro/meso (measured 1.76) is asserted to exceed it, so the
// measure does detect the seam.
TEST(Wang2020Render, NoTextureSeamAtThresholds) {
    const double limit = std::log(2.0);
    EXPECT_GT(largestTextureStep("2.5e5", "0", 1.0, 32.0), limit);
    EXPECT_LT(largestTextureStep("2.5e5", "1", 1.0, 32.0), limit);
    EXPECT_LT(largestTextureStep("3.4e6", "1", 16.0, 256.0), limit);
    // Around E = 64 even the hard switch shows none after the 3-tap glint blur (measured ln 1.16 both ways).
    EXPECT_LT(largestTextureStep("3.4e6", "0", 16.0, 256.0), limit);
}

namespace {
// Expectation of the explicit-particle reference (what it converges to over particle sets): the Beckmann
// microfacet integral of the map, int L(i) D G F / (4 o.n) di, by quadrature over the map box-filtered 4 x 4
// (energy preserving), on a 32 x 32 grid of the view's plane pixels (uv from the G-buffer), times the glint colour.
// The explicit reference with one particle set is a heavy-tailed sample of it under maps with tiny bright lamps
// (studio_small_03 peaks at 3568): its sum fell 34 % short for the sparse material.
double expectedGlintMean(const ImageF& map, const std::vector<float>& uv, glm::vec3 eye, float alpha, glm::vec3 color) {
    const int W = map.width / 4, H = map.height / 4;
    std::vector<glm::dvec3> box(size_t(W) * H, glm::dvec3(0.0));
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i)
                    box[size_t(y) * W + x] += glm::dvec3(map.at(4 * x + i, 4 * y + j, 0), map.at(4 * x + i, 4 * y + j, 1),
                                                         map.at(4 * x + i, 4 * y + j, 2)) / 16.0;
    double total = 0.0;
    int pixels = 0;
    for (int py = 4; py < 256; py += 8)
        for (int px = 4; px < 256; px += 8) {
            size_t p = size_t(py) * 256 + size_t(px);
            if (uv[4 * p + 3] == 0.0f) continue;
            glm::dvec3 o = glm::normalize(glm::dvec3(eye) - glm::dvec3(uv[4 * p], 0.0, uv[4 * p + 1]));
            glm::dvec3 sum(0.0);
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    glm::vec2 t((x + 0.5f) / W, (y + 0.5f) / H);
                    glm::dvec3 i(envref::equirectToDirection(t));
                    if (i.y <= 0.0) continue;
                    double dw = (2.0 * w::kPi / W) * (w::kPi / H) * std::sin(w::kPi * t.y);
                    glm::dvec3 h = glm::normalize(i + o);
                    double f = envref::ndfD(h.y, alpha, envref::kNdfBeckmann) * envref::smithG1(i.y, alpha, envref::kNdfBeckmann) *
                               envref::smithG1(o.y, alpha, envref::kNdfBeckmann) / (4.0 * o.y);
                    sum += box[size_t(y) * W + x] * (f * dw);
                }
            double F = 0.9 + 0.1 * std::pow(1.0 - o.y, 5.0);  // Schlick at n.o, f0 = 0.9 (as the shader)
            total += (sum.x * color.x + sum.y * color.y + sum.z * color.z) / 3.0 * F;
            ++pixels;
        }
    return total / std::max(pixels, 1);
}
}  // namespace

// The README's environment-lit glints next to the CPU reference (the "snow, glitter cloth"): the tilted view
// of the test plane under the studio HDR (--ibl wang2020, lights off, metallic base so only glints are lit), for
// snow-like fine white sparkle (alpha 0.1, gamma 6, N 1e6) and glitter cloth (alpha 0.5, gamma 2, N 1e5, pink
// glint colour). Reference: wang2020::explicitParticleEnvironment on the same footprints and particles, times the
// same Fresnel and colour, then the same 3-tap blur as the shader's post pass (glintpost::referencePostPass).
// Writes shader | reference (shared exposure) to the test output (copied to screenshots/ for the README). Checks
// the total glint energy within 25 % (the paper's Table 1 criterion) of the reference's expectation
// (expectedGlintMean) for both, and of the explicit reference itself for the dense snow (measured: snow 0.89 of
// the reference, 0.88 of the expectation, 0.89 with the visibility forced to 1, so not occlusion; glitter 0.99 of
// the expectation, while one particle set of the reference reaches only 0.66 of it: its few particles that see the
// studio's lamps carry the energy).
TEST(Wang2020Environment, SnowAndGlitterClothNextToReference) {
    useTestCache();
    std::string hdr = assetsDir() + "/hdri/studio_small_03_1k.hdr";
    if (!std::filesystem::exists(hdr)) GTEST_SKIP() << "no " << hdr;
    ImageF image = readImage(hdr);
    struct Look {
        const char* name;
        WangTestMaterial m;
        glm::vec3 color;
    };
    for (const Look& look : {Look{"snow", {0.1f, 6.0f, 1e6f}, {1.0f, 1.0f, 1.0f}},
                             Look{"glitter_cloth", {0.5f, 2.0f, 1e5f}, {1.0f, 0.55f, 0.75f}}}) {
        const WangTestMaterial& m = look.m;
        RenderRequest request = wangEnvironmentRequest(
            m, "tilted", hdr,
            {"wang2020.color_r=" + std::to_string(look.color.x), "wang2020.color_g=" + std::to_string(look.color.y),
             "wang2020.color_b=" + std::to_string(look.color.z)});
        OffscreenSession session(request);
        auto aov = [&](const char* name) { return renderAov(session, request, name); };
        std::vector<float> uv = aov("uv"), dx = aov("duvdx"), dy = aov("duvdy"), shader = aov("final");
        glm::vec3 eye{};
        for (const Camera& c : session.scene().cameras)
            if (c.name == "tilted") eye = c.position;
        w::Quadtree tree = w::buildQuadtree(m.particles, 11, 1);
        std::vector<float> reference(uv.size(), 0.0f), noLights(uv.size(), 0.0f);
        for (size_t p = 0; p < uv.size() / 4; ++p) {
            noLights[4 * p + 3] = 1.0f;   // mask set, no light glints: the occlusion blur leaves visibility 1
            reference[4 * p + 3] = 1.0f;  // visible (a plane under the sky)
            if (shader[4 * p + 3] == 0.0f) continue;  // background
            glm::vec3 L = explicitEnvironmentGlint(tree, footprintAt(uv, dx, dy, p), eye, m.alpha, [&](glm::vec3 world) {
                return envref::sampleEquirect(image, world);
            });
            for (int c = 0; c < 3; ++c) reference[4 * p + size_t(c)] = L[c] * look.color[c];
        }
        std::vector<float> blurred = glintpost::referencePostPass(reference, noLights, 256, 256, 9, 3);
        double gpu = 0, ref = 0;
        std::vector<double> luminance;
        for (size_t p = 0; p < uv.size() / 4; ++p) {
            if (shader[4 * p + 3] == 0.0f) {  // background: the map, not glints (both sides show black)
                for (int c = 0; c < 3; ++c) blurred[4 * p + size_t(c)] = shader[4 * p + size_t(c)] = 0.0f;
                continue;
            }
            for (int c = 0; c < 3; ++c) gpu += shader[4 * p + size_t(c)], ref += blurred[4 * p + size_t(c)];
            luminance.push_back((blurred[4 * p] + blurred[4 * p + 1] + blurred[4 * p + 2]) / 3.0);
        }
        std::sort(luminance.begin(), luminance.end());
        double scale = 0.8 / std::max(luminance[size_t(luminance.size() * 0.995)], 1e-12);
        std::vector<uint8_t> rgba(size_t(512) * 256 * 4, 255);
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x)
                for (int side = 0; side < 2; ++side)
                    for (int c = 0; c < 3; ++c) {
                        size_t p = (size_t(y) * 256 + size_t(x)) * 4 + size_t(c);
                        double v = (side ? blurred[p] : shader[p]) * scale;
                        v = std::pow(std::clamp(v, 0.0, 1.0), 1.0 / 2.2);
                        rgba[(size_t(y) * 512 + size_t(x) + size_t(side) * 256) * 4 + size_t(c)] = uint8_t(std::lround(v * 255));
                    }
        std::filesystem::create_directories(GLIMMER_TEST_OUTPUT_DIR);
        writePng(std::filesystem::path(GLIMMER_TEST_OUTPUT_DIR) / ("wang2020_env_" + std::string(look.name) +
                                                                   "_shader_vs_reference.png"),
                 rgba.data(), 512, 256);
        double plane = 0;
        for (size_t p = 0; p < uv.size() / 4; ++p) plane += shader[4 * p + 3] != 0.0f;
        double expected = expectedGlintMean(image, uv, eye, m.alpha, look.color) * 3.0 * plane;
        std::printf("wang2020 environment (studio, tilted) %s: energy shader %.4g, explicit reference %.4g, its "
                    "expectation %.4g; shader / expectation %.3f, reference / expectation %.3f\n",
                    look.name, gpu, ref, expected, gpu / expected, ref / expected);
        EXPECT_NEAR(gpu / expected, 1.0, 0.25) << look.name;
        if (m.particles >= 1e6f) EXPECT_NEAR(gpu / ref, 1.0, 0.25) << look.name;  // dense: one set converges
    }
}
