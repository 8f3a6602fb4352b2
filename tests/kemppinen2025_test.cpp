// Tests of the kemppinen2025 glint method (Kemppinen et al. 2025): the shader through the real GL pipeline
// (offscreen llvmpipe) against the CPU reference engine/glints/kemppinen2025_reference, convergence to the
// smooth NDF, area-averaged energy (the paper's Fig. 15 furnace), constant cost, and each extension.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numeric>
#include <random>

#include "checks/method_checks.h"
#include "common/bindings.glsl"
#include "core/files.h"
#include "gl/handles.h"
#include "gl/program.h"
#include "glints/glint_mapping.h"
#include "glints/methods.h"
#include "platform/context.h"
#include "reference/kemppinen2025_reference.h"
#include "render/aov.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "render/settings.h"
#include "scene/builtin_scenes.h"
#include "support/measure.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(Kemppinen2025, GlContext);

using namespace glimmer;
namespace k25 = glimmer::kemppinen2025;

namespace {

// One GL context with a built-in scene whose light and meshes the test may change between renders.
class GlintRig {
public:
    explicit GlintRig(const std::string& sceneName) : base_(makeBuiltinScene(sceneName)) {
        base_.environment = "none";   // glints respond to the lights; environment lighting would only add a smooth term
        context_ = createHeadlessContext(Backend::Egl);
        scene_ = base_;
        gpuScene_ = std::make_unique<GpuScene>(scene_);
    }
    ~GlintRig() {
        context_->makeCurrent();
        renderer_.reset();
        gpuScene_.reset();
    }
    Scene& base() { return base_; }
    // Re-uploads the geometry after base().meshes changed.
    void reloadGeometry() {
        context_->makeCurrent();
        scene_ = base_;
        gpuScene_ = std::make_unique<GpuScene>(scene_);
    }
    // Renders the debug view `aov` (or "final") and returns RGBA32F rows, bottom-up.
    std::vector<float> render(const RenderSettings& settingsIn, const std::string& aov, int size,
                              const glm::vec3* towardLight = nullptr) {
        context_->makeCurrent();
        RenderSettings settings = settingsIn;
        settings.debugView = findAov(aov).viewId;
        scene_ = base_;
        if (towardLight) scene_.lights[0].vector = glm::normalize(*towardLight);
        applySceneOverrides(settings, scene_);
        gpuScene_->updateMaterialsAndLights(scene_);
        if (!renderer_)
            renderer_ = std::make_unique<Renderer>(defaultShaderDir(), settings);
        else
            renderer_->setSettings(settings);
        renderer_->renderView(scene_, *gpuScene_, scene_.cameras.front(), size, size);
        glFinish();
        return renderer_->readHdr();
    }
    const Scene& scene() const { return scene_; }

private:
    std::unique_ptr<GLContext> context_;
    Scene base_, scene_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::unique_ptr<Renderer> renderer_;
};

RenderSettings kemppinen(std::initializer_list<std::pair<const char*, float>> params, int ndf = 0,
                         float alpha = 0.3f) {
    RenderSettings s;
    s.method = "kemppinen2025";
    s.common["material.ndf"] = float(ndf);
    s.common["material.alpha"] = alpha;
    for (auto& [k, v] : params) s.methods["kemppinen2025"][k] = v;
    return s;
}

RenderSettings smoothSettings(int ndf, float alpha = 0.3f) {
    RenderSettings s;
    s.method = "smooth";
    s.common["material.ndf"] = float(ndf);
    s.common["material.alpha"] = alpha;
    return s;
}

std::vector<float> channel(const std::vector<float>& rgba, int c) {
    std::vector<float> out(rgba.size() / 4);
    for (size_t i = 0; i < out.size(); ++i) out[i] = rgba[4 * i + c];
    return out;
}

double mean(const std::vector<float>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()); }

// Box-filtered (block x block) copy of a size x size single-channel image.
std::vector<double> boxFilter(const std::vector<float>& img, int size, int block) {
    int n = size / block;
    std::vector<double> out(size_t(n) * n, 0.0);
    for (int y = 0; y < n * block; ++y)
        for (int x = 0; x < n * block; ++x) out[(y / block) * n + x / block] += img[size_t(y) * size + x];
    for (double& v : out) v /= block * block;
    return out;
}

double correlation(const std::vector<float>& a, const std::vector<float>& b) {
    double ma = mean(a), mb = mean(b), sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return sab / std::sqrt(std::max(saa * sbb, 1e-300));
}

// World position of a pixel centre of the camera's view of the plane y = 0 (the plane scenes), in double.
glm::dvec3 planePoint(const Camera& camera, int size, double px, double py) {
    glm::dmat4 invVp = glm::inverse(glm::dmat4(camera.projection(1.0f)) * glm::dmat4(camera.view()));
    glm::dvec4 ndc((px) / size * 2.0 - 1.0, (py) / size * 2.0 - 1.0, 0.5, 1.0);
    glm::dvec4 p = invVp * ndc;
    glm::dvec3 eye(camera.position);
    glm::dvec3 dir = glm::dvec3(p) / p.w - eye;
    return eye + dir * (-eye.y / dir.y);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// CPU-only checks of the mappings (Sec. 3.2.1-3.2.2).

TEST(Kemppinen2025, PriorMappingsRoundTripAndPushTheNdfToUniform) {
    for (int ndf : {k25::kGgx, k25::kBeckmann})
        for (glm::dvec2 alpha : {glm::dvec2(0.3), glm::dvec2(0.1, 0.5)}) {
            std::mt19937 rng(7);
            std::uniform_real_distribution<double> u(0.0, 1.0);
            for (int i = 0; i < 2000; ++i) {
                glm::dvec2 x(u(rng), u(rng));
                if (glm::dot(x - 0.5, x - 0.5) > 0.24) continue;
                glm::dvec3 h = k25::fromPrior(x, alpha, ndf);
                glm::dvec2 back = k25::toPrior(h, alpha, ndf);
                ASSERT_NEAR(back.x, x.x, 1e-9);
                ASSERT_NEAR(back.y, x.y, 1e-9);
                // Jacobian of T (solid angle -> prior area) by finite differences: proportional to D (GGX,
                // Eq. 6-7: uniform prior <-> D dw) or D cos (Beckmann, Marsaglia: uniform disk <-> slopes).
                double e = 1e-5;
                glm::dvec3 hx = k25::fromPrior(x + glm::dvec2(e, 0), alpha, ndf);
                glm::dvec3 hy = k25::fromPrior(x + glm::dvec2(0, e), alpha, ndf);
                double solidAngle = glm::length(glm::cross(hx - h, hy - h));
                double jacobian = e * e / solidAngle;
                // GGX: the paper's |J_M~| = |M| / |M^T h|^4 (Eq. 6) is the NDF's transformation rule; as a
                // solid-angle Jacobian M~ contributes |M| / |M^T h|^3, so T's Jacobian is pi D |M^T h| / 8
                // (L halves areas, the radius-1/2 disk quarters them). Beckmann: pi D cos / 4.
                double pi = 3.14159265358979;
                double stretch = glm::length(glm::dvec3(h.x / alpha.x, h.y / alpha.y, h.z));
                double expected = ndf == k25::kGgx ? pi * k25::smoothD(h, alpha, ndf) * stretch / 8.0
                                                   : pi * k25::smoothD(h, alpha, ndf) * h.z / 4.0;
                ASSERT_NEAR(jacobian / expected, 1.0, 2e-3) << "ndf " << ndf << " x " << x.x << "," << x.y;
            }
        }
}

// ---------------------------------------------------------------------------------------------------------
// Shader against the CPU reference, pixel by pixel (GGX, Beckmann, anisotropies, k = 16, colour).

static void expectShaderMatchesCpu(GlintRig& rig, const RenderSettings& settings, int size, const char* label) {
    auto uv = rig.render(settings, "uv", size);
    auto dx = rig.render(settings, "duvdx", size);
    auto dy = rig.render(settings, "duvdy", size);
    auto glint = rig.render(settings, "glint", size);
    // The smooth method's D at the same pixels: dividing both sides by their own smooth D compares the glint
    // structure without the ~5e-4 difference between the lighting pass's half vector (position rebuilt from
    // float depth) and the CPU's exact one, which the smooth method shows as well.
    RenderSettings smooth = settings;
    smooth.method = "smooth";
    auto smoothGlint = rig.render(smooth, "glint", size);
    const Scene& scene = rig.scene();
    const Camera& camera = scene.cameras.front();
    glm::dvec3 toLight = glm::normalize(glm::dvec3(scene.lights[0].vector));
    // The shader reads the plane's glint material mapped to the method's parameters (glint_mapping.h), with the
    // test's --set values on top: the reference takes the same values.
    const Material& plane = *std::find_if(scene.materials.begin(), scene.materials.end(),
                                          [](const Material& m) { return m.glinty; });
    k25::Params params = k25::paramsFrom(
        materialParams(findGlintMethod("kemppinen2025"), plane, settings.methodValues("kemppinen2025")));
    int compared = 0, failed = 0;
    double sumGpu = 0, sumCpu = 0, sumSmooth = 0;
    int failedBadly = 0;
    std::vector<double> errors;
    for (int y = 0; y < size; y += 3)
        for (int x = 0; x < size; x += 3) {
            size_t i = size_t(y) * size + x;
            k25::Surface s;
            s.uv = {uv[4 * i], uv[4 * i + 1]};
            s.duvdx = {dx[4 * i], dx[4 * i + 1]};
            s.duvdy = {dy[4 * i], dy[4 * i + 1]};
            s.alpha = settings.value(param::material_alpha);
            s.ndf = int(settings.value(param::material_ndf));
            glm::dvec3 p = planePoint(camera, size, x + 0.5, y + 0.5);
            s.position = p;
            s.normal = {0, 1, 0};
            s.dPdx = planePoint(camera, size, x + 1.5, y + 0.5) - p;
            s.dPdy = planePoint(camera, size, x + 0.5, y + 1.5) - p;
            glm::dvec3 wo = glm::normalize(glm::dvec3(camera.position) - p);
            glm::dvec3 hw = glm::normalize(wo + toLight);
            glm::dvec3 h(hw.x, hw.z, hw.y);   // shading frame of the plane: t = +x, b = +z, n = +y
            double smooth = k25::smoothD(h, k25::splitAlpha(s.alpha, params.roughnessAnisotropy), s.ndf);
            double smoothIso = k25::smoothD(h, glm::dvec2(s.alpha), s.ndf);
            double cpu = glm::dot(k25::filteredNdf(params, s, h), glm::dvec3(1.0 / 3.0));
            double gpu = glint[4 * i] * smoothIso / std::max(double(smoothGlint[4 * i]), 1e-30);
            ++compared;
            sumGpu += gpu;
            sumCpu += cpu;
            errors.push_back(std::abs(gpu - cpu) / std::max(cpu, 0.05 * smooth));
            if (std::abs(gpu - cpu) > 1e-2 * std::max(cpu, 0.05 * smooth) + 1e-6) ++failed;
            if (std::abs(gpu - cpu) > 1e-1 * std::max(cpu, 0.05 * smooth) + 1e-6) ++failedBadly;
            sumSmooth += smooth;
        }
    std::sort(errors.begin(), errors.end());
    std::printf("[%s] shader vs CPU: relative error median %.2g, 95%% %.2g, 99%% %.2g; %d of %d sampled pixels "
                "differ by > 1%%; means %.5g (GL) %.5g (CPU)\n",
                label, errors[errors.size() / 2], errors[errors.size() * 95 / 100], errors[errors.size() * 99 / 100],
                failed, compared, sumGpu / compared, sumCpu / compared);
    // Residual differences: the shader works in float32 on UVs near 64 m (ulp 7.6e-6 m, ~1e-4 of a spatial
    // cell), and the lighting pass's half vector differs from the CPU's by ~1e-4 rad (the smooth method shows
    // the same 5e-4 relative difference in D): sharp glints seen in their tails then differ by up to tens of
    // percent in about 0.5% of pixels; the compensation-dominated (dense) case agrees to 1e-5.
    EXPECT_LE(failed, compared * 3 / 100) << label;
    EXPECT_LE(failedBadly, compared / 100) << label;
    EXPECT_LE(std::abs(sumGpu - sumCpu), 5e-3 * sumSmooth) << label;
}

TEST(Kemppinen2025, ShaderMatchesCpuReference) {
    GlintRig rig("plane90");
    expectShaderMatchesCpu(rig, kemppinen({}, 0), 96, "ggx default");
    expectShaderMatchesCpu(rig, kemppinen({{"density", 1e12f}}, 0), 96, "ggx dense");
    expectShaderMatchesCpu(rig, kemppinen({{"density", 1e2f}}, 0), 96, "ggx sparse");
    expectShaderMatchesCpu(rig, kemppinen({}, 1), 96, "beckmann default");
    expectShaderMatchesCpu(rig, kemppinen({{"density", 3e8f}, {"neighbors", 1.0f}}, 0), 96, "ggx k=16");
    // At the plane's density itself (2e6 per UV area), as before issue 36 mapped the material to a tenth of it:
    // the sparser, sharper anisotropic glints put more pixels in the float32 tails this comparison tolerates.
    expectShaderMatchesCpu(rig, kemppinen({{"glint_anisotropy", 8.0f}, {"roughness_anisotropy", 3.0f}, {"density", 2e6f}}, 1),
                           96, "beckmann anisotropic");
    expectShaderMatchesCpu(rig, kemppinen({{"color_variation", 1.0f}, {"micro_roughness", 0.03f}}, 0), 96,
                           "ggx coloured");
    expectShaderMatchesCpu(rig, kemppinen({{"triplanar", 1.0f}}, 0), 96, "ggx triplanar");
}

TEST(Kemppinen2025, ShaderMatchesCpuReferenceAtGrazingAngles) {
    GlintRig rig("plane25");
    expectShaderMatchesCpu(rig, kemppinen({}, 0), 96, "plane25 ggx");
    expectShaderMatchesCpu(rig, kemppinen({{"density", 1e13f}}, 1), 96, "plane25 beckmann dense");
    // Low roughness: Beckmann's D underflows over much of the view (no NaN may come out of the tails).
    expectShaderMatchesCpu(rig, kemppinen({}, 1, 0.1f), 96, "plane25 beckmann alpha 0.1");
}

// ---------------------------------------------------------------------------------------------------------
// Convergence: very high density and small micro-roughness give the smooth render (Eq. 2 in practice).

struct GapStats {
    double meanGap = 0.0, worstBlockGap = 0.0;
};

// `b`: the smooth render of the same scene, NDF and size (rig.render(smoothSettings(ndf), "final", size)).
static GapStats gapToSmooth(GlintRig& rig, const RenderSettings& glinty, const std::vector<float>& b, int size) {
    auto a = rig.render(glinty, "final", size);
    GapStats g;
    double sa = 0, sb = 0;
    for (int c = 0; c < 3; ++c) {
        auto ca = channel(a, c), cb = channel(b, c);
        sa += mean(ca);
        sb += mean(cb);
        auto fa = boxFilter(ca, size, 4), fb = boxFilter(cb, size, 4);
        double peak = *std::max_element(fb.begin(), fb.end());
        for (size_t i = 0; i < fa.size(); ++i)
            if (fb[i] > 1e-3 * peak) {
                g.worstBlockGap = std::max(g.worstBlockGap, std::abs(fa[i] / fb[i] - 1.0));
            }
    }
    g.meanGap = std::abs(sa / sb - 1.0);
    return g;
}

// check-method's finite rule (40,824 footprints x angles x roughnesses, engine/checks/method_checks.cpp) once
// found 780 NaN and then one Inf: duv/dx about 1e4 UV with nearly parallel derivatives made det(Sigma_s) round
// to zero or below, and the quadratic form of its nearly singular inverse negative. Every value must be finite.
TEST(Kemppinen2025, FiniteAtDegenerateHugeFootprints) {
    checks::CheckOptions options;
    options.rules = {"finite"};
    checks::CheckReport report = checks::checkMethod("kemppinen2025", options);
    std::string table = checks::formatTable(report);
    ASSERT_EQ(report.results.size(), 1u);
    EXPECT_TRUE(report.passed()) << table;
}

// Asserted at micro_roughness 0.01; the rows at 0.03 and 0.1 are a measurement of how the gap grows (nothing is
// asserted on them) and are rendered with GLIMMER_MEASURE=1 only. The smooth render of each NDF is shared by
// its rows (deterministic: a second render gives the same floats).
TEST(Kemppinen2025, HighDensityConvergesToSmooth) {
    const int size = 128;
    std::vector<float> micros = {0.01f};
    if (test::fullMeasurement()) micros = {0.01f, 0.03f, 0.1f};
    std::printf("scene    ndf       micro_roughness  mean gap  worst 4x4-block gap\n");
    for (const char* sceneName : {"plane90", "plane25"}) {
        GlintRig rig(sceneName);
        for (int ndf : {0, 1}) {
            std::vector<float> smooth = rig.render(smoothSettings(ndf), "final", size);
            for (float micro : micros) {
                GapStats g = gapToSmooth(rig, kemppinen({{"density", 1e13f}, {"micro_roughness", micro}}, ndf),
                                         smooth, size);
                std::printf("%-8s %-9s %-16.3f %-9.4f %.4f\n", sceneName, ndf ? "beckmann" : "ggx", micro, g.meanGap,
                            g.worstBlockGap);
                if (micro == 0.01f) {
                    EXPECT_LT(g.meanGap, 0.03) << sceneName << " ndf " << ndf;
                    // Beckmann at 25 degrees: half vectors 30 degrees off the normal map to within 0.005 of the
                    // prior square's edge (the Marsaglia map packs the Gaussian tail into the rim), where the
                    // glint lobes leak out of U and the square: the energy loss at domain boundaries the paper
                    // states (Sec. 5). There the per-block gap reaches ~18% in the image corners; the mean holds.
                    if (!(ndf == 1 && std::string(sceneName) == "plane25"))
                        EXPECT_LT(g.worstBlockGap, 0.03) << sceneName << " ndf " << ndf;
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------------------
// Furnace (the paper's Fig. 15): area-averaged projected-area NDF integral int D*^f cos dw, relative to the
// smooth NDF's (which is 1), for a sweep of roughness, micro-roughness and footprint (LOD). CPU reference (the
// shader is tied to it by ShaderMatchesCpuReference). Estimator: uniform points (x, u) over a 64x64-cell patch
// and the prior space, w = T^-1(u), weights cos / |J_T|; ratio to the smooth integrand on the same samples.

TEST(Kemppinen2025, FurnaceAreaAveragedEnergy) {
    const double pi = 3.14159265358979;
    // Measured minimum 0.232 (Beckmann, alpha 0.1, alpha* 0.1: lobes as wide as the prior square leak out of
    // it, Fig. 14 right / Sec. 5; 0.416 with angular_covariance=d, whose lobes are sqrt(pi) narrower than the
    // authors' default d = pi D); pairs with alpha* <= alpha / 10 stay above 0.95.
    const double floorBound = 0.20;
    std::printf("ndf       alpha  micro   lambda  energy/smooth  (std err, samples, estimator)\n");
    double lowest = 1e9, highest = 0;
    for (int ndf : {k25::kGgx, k25::kBeckmann})
        for (double alpha : {0.1, 0.3, 0.6})
            for (double micro : {0.003, 0.01, 0.03, 0.1})
                for (double footprint : {3e-4, 2e-3, 4e-2}) {
                    k25::Params params;
                    params.microRoughness = micro;
                    params.density = 2e6;
                    k25::Surface s;
                    s.alpha = alpha;
                    s.ndf = ndf;
                    s.duvdx = {footprint, 0.0};
                    s.duvdy = {0.0, footprint * 0.77};
                    std::mt19937_64 rng(1234);
                    std::uniform_real_distribution<double> u01(0.0, 1.0);
                    // 40000 samples uniform in the prior; spiky (explicit-dominated) cases whose standard error
                    // stays above 1.5% are re-estimated with the glint importance sampler (Algorithm 2, tested
                    // below): E = E_x E_{h ~ p}[D*^f(x, h) cos / p(h)] against the smooth NDF's exact 1.
                    int n = 0;
                    double sumGlint = 0, sumSmooth = 0, sumSq = 0, lambda = 0, stdErr = 1.0;
                    const char* estimator = "uniform";
                    while (n < 40000) {
                      for (int batch = 0; batch < 40000; ++batch) {
                        ++n;
                        glm::dvec2 u(u01(rng), u01(rng));
                        if (glm::dot(u - 0.5, u - 0.5) >= 0.25) continue;
                        glm::dvec3 h = k25::fromPrior(u, glm::dvec2(alpha), ndf);
                        double d = k25::smoothD(h, glm::dvec2(alpha), ndf);
                        double stretch = glm::length(glm::dvec3(h.x / alpha, h.y / alpha, h.z));
                        double jacobian = ndf == k25::kGgx ? pi * d * stretch / 8.0 : pi * d * h.z / 4.0;
                        double weight = h.z / jacobian;
                        // A random surface point over a patch of 64 x 64 level cells around UV 64.
                        double cell = 64.0 / std::sqrt(params.density) * std::max(1.0, footprint * 6.0 * 1414.2);
                        s.uv = glm::dvec2(64.0) + cell * glm::dvec2(u01(rng), u01(rng));
                        k25::PixelSetup px = k25::setupPixel(params, s);
                        lambda = px.process[0].lambda;
                        double g = glm::dot(k25::filteredNdf(params, px, ndf, h), glm::dvec3(1.0 / 3.0)) * weight;
                        sumGlint += g;
                        sumSq += g * g;
                        sumSmooth += d * weight;
                      }
                      double meanG = sumGlint / n, var = sumSq / n - meanG * meanG;
                      stdErr = std::sqrt(std::max(var, 0.0) / n) / (sumSmooth / n);
                    }
                    double ratio = sumGlint / sumSmooth;
                    if (stdErr > 0.015) {
                        estimator = "glint IS";
                        k25::SamplerRng samplerRng(777);
                        const int m = 12000;
                        double sum = 0.0, sum2 = 0.0;
                        for (int i = 0; i < m; ++i) {
                            double cell = 64.0 / std::sqrt(params.density) * std::max(1.0, footprint * 6.0 * 1414.2);
                            s.uv = glm::dvec2(64.0) + cell * glm::dvec2(u01(rng), u01(rng));
                            k25::PixelSetup px = k25::setupPixel(params, s);
                            k25::HalfVectorSample hs = k25::sampleHalfVector(params, px, ndf, samplerRng);
                            double v = 0.0;
                            if (hs.pdf > 0.0)
                                v = glm::dot(k25::filteredNdf(params, px, ndf, hs.h), glm::dvec3(1.0 / 3.0)) * hs.h.z /
                                    hs.pdf;
                            sum += v;
                            sum2 += v * v;
                        }
                        ratio = sum / m;
                        stdErr = std::sqrt(std::max(sum2 / m - ratio * ratio, 0.0) / m);
                        n = m;
                    }
                    std::printf("%-9s %-6.2f %-7.3f %-7.2f %-14.4f (%.4f, %d, %s)\n", ndf ? "beckmann" : "ggx", alpha,
                                micro, lambda, ratio, stdErr, n, estimator);
                    lowest = std::min(lowest, ratio);
                    highest = std::max(highest, ratio);
                    EXPECT_LE(ratio - 3.0 * stdErr, 1.05) << "alpha " << alpha << " micro " << micro;
                    EXPECT_GE(ratio + 3.0 * stdErr, floorBound) << "alpha " << alpha << " micro " << micro;
                }
    std::printf("energy/smooth range: %.4f .. %.4f\n", lowest, highest);
}

// ---------------------------------------------------------------------------------------------------------
// Constant cost: the number of Gaussian-pair evaluations per pixel (glintExtraAOV x) is 2 levels x k angular
// x 4 spatial cells per light (x 3 processes in triplanar mode), whatever the footprint and the density.

TEST(Kemppinen2025, ConstantGaussianCountWhateverTheFootprint) {
    GlintRig rig("plane25");
    const int size = 96;
    struct Case {
        RenderSettings settings;
        int expected;
    };
    std::vector<Case> cases = {
        {kemppinen({{"density", 1e4f}}), 32},
        {kemppinen({{"density", 1e12f}}), 32},
        {kemppinen({{"neighbors", 1.0f}}), 128},
        {kemppinen({{"triplanar", 1.0f}}), 96},
    };
    RenderSettings three = kemppinen({});
    three.common["light.count"] = 3;
    cases.push_back({three, 96});
    for (const Case& c : cases) {
        auto extra = rig.render(c.settings, "extra", size);
        auto depth = rig.render(c.settings, "depth", size);
        int covered = 0, wrong = 0;
        double minLambda = 1e9, maxLambda = -1e9;
        for (size_t i = 0; i < extra.size() / 4; ++i) {
            if (depth[4 * i] <= 0.0f) continue;   // sky
            ++covered;
            wrong += int(extra[4 * i] + 0.5f) != c.expected;
            minLambda = std::min(minLambda, double(extra[4 * i + 1]));
            maxLambda = std::max(maxLambda, double(extra[4 * i + 1]));
        }
        std::printf("expected %d Gaussian pairs per pixel: %d of %d covered pixels differ; LOD %.2f .. %.2f\n",
                    c.expected, wrong, covered, minLambda, maxLambda);
        EXPECT_GT(covered, size * size / 2);
        EXPECT_EQ(wrong, 0);
        EXPECT_GT(maxLambda - minLambda, 3.0);   // the footprints really span several levels
    }
}

// ---------------------------------------------------------------------------------------------------------
// Extensions (Sec. 3.3.6).

static glm::vec3 rotated(glm::vec3 v, glm::vec3 axis, float angle) {
    return glm::vec3(glm::rotate(glm::mat4(1.0f), angle, axis) * glm::vec4(v, 0.0f));
}

// Glint anisotropy stretches each glint's angular lobe along the tangent (A*^-1 on Sigma_a): moving the half
// vector along the tangent keeps the same glints lit, moving it along the bitangent switches them.
TEST(Kemppinen2025, AnisotropyStretchesGlintLobesAlongTheTangent) {
    GlintRig rig("plane90");
    const int size = 96;
    glm::vec3 light = glm::normalize(rig.base().lights[0].vector);
    const float delta = 0.015f;   // isotropic glints (alpha* = 0.02) decorrelate to ~0.7 over this move
    glm::vec3 alongTangent = rotated(light, {0, 0, 1}, delta);    // moves h along world x = tangent
    glm::vec3 alongBitangent = rotated(light, {1, 0, 0}, delta);  // moves h along world z = bitangent
    auto glintOverSmooth = [&](const RenderSettings& s, const glm::vec3& l) {
        RenderSettings sm = s;
        sm.method = "smooth";
        auto g = channel(rig.render(s, "glint", size, &l), 0);
        auto d = channel(rig.render(sm, "glint", size, &l), 0);
        for (size_t i = 0; i < g.size(); ++i) g[i] /= std::max(d[i], 1e-12f);
        return g;
    };
    double correlations[2][2];
    for (int a = 0; a < 2; ++a) {
        // alpha* = 0.02 / sqrt(pi): the lobe of alpha* = 0.02 with d = D(h), which delta was chosen for (the
        // default d = pi D(h) widens lobes by sqrt(pi)).
        RenderSettings s = kemppinen({{"micro_roughness", 0.02f / 1.7724539f}, {"glint_anisotropy", a ? 16.0f : 1.0f}});
        auto base = glintOverSmooth(s, light);
        correlations[a][0] = correlation(base, glintOverSmooth(s, alongTangent));
        correlations[a][1] = correlation(base, glintOverSmooth(s, alongBitangent));
        std::printf("glint_anisotropy %2d: correlation after moving h along tangent %.3f, along bitangent %.3f\n",
                    a ? 16 : 1, correlations[a][0], correlations[a][1]);
    }
    EXPECT_NEAR(correlations[0][0], correlations[0][1], 0.15);   // isotropic: same decorrelation both ways
    EXPECT_GT(correlations[1][0], correlations[1][1] + 0.3);     // anisotropic: long along the tangent
    EXPECT_LT(correlations[1][1], correlations[0][1]);
}

// Per-glint colours: glints take different hues, while the area mean colour (what the compensation term uses)
// stays that of the uncoloured material.
TEST(Kemppinen2025, ColouredGlintsKeepTheMeanColour) {
    GlintRig rig("plane90");
    const int size = 128;
    // Sparse enough that explicit glints (not the white compensation) make most of the highlight.
    auto plain = rig.render(kemppinen({{"density", 2e4f}, {"micro_roughness", 0.02f}}), "final", size);
    auto coloured = rig.render(kemppinen({{"density", 2e4f}, {"micro_roughness", 0.02f}, {"color_variation", 1.0f}}),
                               "final", size);
    auto chroma = [&](const std::vector<float>& img) {
        double sum = 0;
        int n = 0;
        for (size_t i = 0; i < img.size() / 4; ++i) {
            float r = img[4 * i], g = img[4 * i + 1], b = img[4 * i + 2];
            float m = (r + g + b) / 3.0f;
            if (m < 1e-3f) continue;
            sum += (std::max({r, g, b}) - std::min({r, g, b})) / m;
            ++n;
        }
        return sum / std::max(n, 1);
    };
    double chromaPlain = chroma(plain), chromaColoured = chroma(coloured);
    std::printf("mean per-pixel chroma: %.4f plain, %.4f coloured; channel means ratio", chromaPlain, chromaColoured);
    EXPECT_GT(chromaColoured, chromaPlain + 0.3);
    for (int c = 0; c < 3; ++c) {
        double ratio = mean(channel(coloured, c)) / mean(channel(plain, c));
        std::printf(" %.4f", ratio);
        EXPECT_NEAR(ratio, 1.0, 0.05) << "channel " << c;
    }
    std::printf("\n");
}

// UV-free (triplanar) mode: the image does not depend on the mesh's UVs at all, and it converges to the smooth
// NDF like the UV mode.
TEST(Kemppinen2025, TriplanarModeIgnoresUvs) {
    GlintRig rig("plane90");
    const int size = 96;
    RenderSettings triplanar = kemppinen({{"triplanar", 1.0f}});
    RenderSettings uvMode = kemppinen({});
    auto withUvs = rig.render(triplanar, "glint", size);
    auto uvModeWithUvs = rig.render(uvMode, "glint", size);
    for (glm::vec2& uv : rig.base().meshes[0].uvs) uv = glm::vec2(0.0f);   // a mesh without UVs
    rig.reloadGeometry();
    auto withoutUvs = rig.render(triplanar, "glint", size);
    auto uvModeWithoutUvs = rig.render(uvMode, "glint", size);
    double triplanarDiff = 0, uvDiff = 0;
    for (size_t i = 0; i < withUvs.size(); i += 4) {
        triplanarDiff = std::max(triplanarDiff, double(std::abs(withUvs[i] - withoutUvs[i])));
        uvDiff = std::max(uvDiff, double(std::abs(uvModeWithUvs[i] - uvModeWithoutUvs[i])));
    }
    std::printf("max |D| change when UVs are removed: triplanar %.3g, UV mode %.3g\n", triplanarDiff, uvDiff);
    EXPECT_EQ(triplanarDiff, 0.0);
    EXPECT_GT(uvDiff, 0.5);
    // Dense triplanar glints converge to the smooth render as well.
    GapStats g = gapToSmooth(rig, kemppinen({{"triplanar", 1.0f}, {"density", 1e13f}}),
                             rig.render(smoothSettings(0), "final", size), size);
    EXPECT_LT(g.meanGap, 0.03);
    EXPECT_LT(g.worstBlockGap, 0.03);
}

// Spatially varying density: the material/texture scale multiplies the density; zero means no glints.
TEST(Kemppinen2025, DensityScaleMultipliesDensity) {
    GlintRig rig("plane90");
    const int size = 64;
    RenderSettings scaled = kemppinen({{"density", 1e6f}});
    scaled.common["material.density_scale"] = 4.0f;
    auto a = rig.render(scaled, "glint", size);
    auto b = rig.render(kemppinen({{"density", 4e6f}}), "glint", size);
    EXPECT_EQ(a, b);
    scaled.common["material.density_scale"] = 0.0f;
    auto none = channel(rig.render(scaled, "glint", size), 0);
    EXPECT_EQ(*std::max_element(none.begin(), none.end()), 0.0f);
}

// ---------------------------------------------------------------------------------------------------------
// Importance sampling (Sec. 3.3.5, Algorithm 2) in a standalone compute shader: the returned pdf is the density
// of the samples (pdf agreement with the CPU twin, chi-square of the histogram against the integrated pdf), and
// Monte Carlo with it reproduces quadrature of the evaluated lobe, int D*^f cos dw, within 1%.

namespace {

struct SamplingCase {
    const char* label;
    int ndf;
    double alpha, micro, footprint;
};

void runSamplingCase(const SamplingCase& c) {
    auto context = createHeadlessContext(Backend::Egl);
    const GlintMethod& method = findGlintMethod("kemppinen2025");
    ParamValues values{{"micro_roughness", float(c.micro)}, {"density", 2e6f}};
    gl::ProgramDesc desc;
    desc.name = "kemppinen2025 sampling test";
    desc.stages = {{GL_COMPUTE_SHADER, "glints/kemppinen2025/kemppinen2025_sampling_test.glsl"}};
    desc.preamble = methodParamsGlsl(method);
    gl::Program program(defaultShaderDir(), desc);
    std::vector<float> packed = packMethodParams(method, values);
    gl::Buffer paramBuffer = gl::createBuffer(GLsizeiptr(packed.size() * sizeof(float)), packed.data());
    gl::Buffer frameBuffer = gl::createBuffer(1024, nullptr);   // unused by the sampler, bound for completeness
    const uint32_t n = 1u << 17;
    gl::Buffer samples = gl::createBuffer(GLsizeiptr(n) * 16, nullptr);
    gl::Buffer priors = gl::createBuffer(GLsizeiptr(n) * 8, nullptr);
    glm::dvec2 uv(64.3, 64.7);
    k25::Params params = k25::paramsFrom(values);
    k25::Surface s;
    s.uv = uv;
    s.duvdx = {c.footprint, 0.0};
    s.duvdy = {0.0, c.footprint * 0.77};
    s.alpha = c.alpha;
    s.ndf = c.ndf;
    program.use();
    glUniform2f(0, float(uv.x), float(uv.y));
    glUniform4f(1, float(s.duvdx.x), float(s.duvdx.y), float(s.duvdy.x), float(s.duvdy.y));
    glUniform1f(2, float(c.alpha));
    glUniform1i(3, c.ndf);
    glUniform1ui(4, n);
    glUniform1ui(5, 12345u);
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_FRAME, frameBuffer.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_METHOD_PARAMS, paramBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_RIG_OUTPUT, samples.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_RIG_OUTPUT_2, priors.id());
    glDispatchCompute(n / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> hs(n);
    std::vector<glm::vec2> xs(n);
    glGetNamedBufferSubData(samples.id(), 0, GLsizeiptr(n) * 16, hs.data());
    glGetNamedBufferSubData(priors.id(), 0, GLsizeiptr(n) * 8, xs.data());

    k25::PixelSetup px = k25::setupPixel(params, s);
    // 1. The shader's pdf is the CPU twin's at the same half vectors.
    int checked = 0, pdfMismatch = 0, valid = 0;
    for (uint32_t i = 0; i < n; ++i) {
        if (!(hs[i].w > 0.0f)) continue;
        ++valid;
        if (i % 32 != 0) continue;
        double cpu = k25::sampleSolidAnglePdf(params, px, c.ndf, glm::dvec3(hs[i]));
        ++checked;
        if (std::abs(hs[i].w - cpu) > 1e-2 * cpu) ++pdfMismatch;
    }
    std::printf("[%s] lambda %.2f: %d of %u samples valid; pdf GL vs CPU differs by > 1%% at %d of %d\n", c.label,
                px.process[0].lambda, valid, n, pdfMismatch, checked);
    EXPECT_LE(pdfMismatch, checked / 100) << c.label;
    // x_a is uniform over the prior square, so blocks outside the disk U waste a few samples.
    EXPECT_GT(valid, int(n * 0.85)) << c.label;

    // 2. Chi-square of the prior-space histogram against the integrated pdf (16 x 16 bins, 12 x 12 midpoints).
    const int bins = 16, sub = 12;
    std::vector<double> observed(bins * bins, 0.0), expected(bins * bins, 0.0), ndfMass(bins * bins, 0.0);
    for (uint32_t i = 0; i < n; ++i)
        if (hs[i].w > 0.0f) {
            int bx = std::clamp(int(xs[i].x * bins), 0, bins - 1), by = std::clamp(int(xs[i].y * bins), 0, bins - 1);
            observed[by * bins + bx] += 1.0;
        }
    double cell = 1.0 / (bins * sub), ndfTotal = 0.0;
    for (int by = 0; by < bins; ++by)
        for (int bx = 0; bx < bins; ++bx)
            for (int j = 0; j < sub; ++j)
                for (int i = 0; i < sub; ++i) {
                    glm::dvec2 x((bx * sub + i + 0.5) * cell, (by * sub + j + 0.5) * cell);
                    expected[by * bins + bx] += n * k25::samplePriorPdf(params, px, c.ndf, x) * cell * cell;
                    if (glm::dot(x - 0.5, x - 0.5) >= 0.25) continue;
                    glm::dvec3 h = k25::fromPrior(x, px.alpha, c.ndf);
                    double f = glm::dot(k25::filteredNdf(params, px, c.ndf, h), glm::dvec3(1.0 / 3.0)) * h.z /
                               k25::priorJacobian(h, px.alpha, c.ndf);
                    ndfMass[by * bins + bx] += f * cell * cell;
                    ndfTotal += f * cell * cell;
                }
    double chi2 = 0.0, tvToNdf = 0.0;
    int dof = -1;
    for (int b = 0; b < bins * bins; ++b) {
        tvToNdf += 0.5 * std::abs(observed[b] / valid - ndfMass[b] / ndfTotal);
        if (expected[b] < 20.0) continue;
        chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
        ++dof;
    }
    // 0.999 quantile of chi-square (Wilson-Hilferty).
    double z = 3.09, k = dof;
    double limit = k * std::pow(1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k)), 3.0);
    std::printf("[%s] chi-square %.1f with %d dof (0.999 quantile %.1f); total variation between the sample "
                "histogram and the evaluated NDF %.3f\n", c.label, chi2, dof, limit, tvToNdf);
    EXPECT_LT(chi2, limit) << c.label;

    // 3. Monte Carlo with the returned pdf against quadrature of the evaluated lobe.
    double sum = 0.0, sumSq = 0.0;
    for (uint32_t i = 0; i < n; ++i) {
        double v = 0.0;
        if (hs[i].w > 0.0f) {
            glm::dvec3 h(hs[i]);
            v = glm::dot(k25::filteredNdf(params, px, c.ndf, h), glm::dvec3(1.0 / 3.0)) * h.z / hs[i].w;
        }
        sum += v;
        sumSq += v * v;
    }
    double mc = sum / n, stdErr = std::sqrt(std::max(sumSq / n - mc * mc, 0.0) / n);
    // Quadrature over the prior disk (384 x 384 midpoints; lobes are wider than 2 cells here).
    const int grid = 384;
    double quad = 0.0, dq = 1.0 / grid;
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            glm::dvec2 x((i + 0.5) * dq, (j + 0.5) * dq);
            if (glm::dot(x - 0.5, x - 0.5) >= 0.25) continue;
            glm::dvec3 h = k25::fromPrior(x, px.alpha, c.ndf);
            quad += glm::dot(k25::filteredNdf(params, px, c.ndf, h), glm::dvec3(1.0 / 3.0)) * h.z /
                    k25::priorJacobian(h, px.alpha, c.ndf) * dq * dq;
        }
    std::printf("[%s] int D*^f cos: Monte Carlo %.5f (std err %.5f, %u samples) vs quadrature %.5f\n", c.label, mc,
                stdErr, n, quad);
    EXPECT_NEAR(mc / quad, 1.0, 0.01) << c.label;

    // 4. Fig. 7's claim: lower variance than sampling the smooth NDF (uniform prior through T^-1), same count.
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    double sumSmooth = 0.0, sumSqSmooth = 0.0;
    for (uint32_t i = 0; i < n; ++i) {
        double r = 0.5 * std::sqrt(u01(rng)), phi = 2.0 * 3.14159265358979 * u01(rng);
        glm::dvec2 x = 0.5 + r * glm::dvec2(std::cos(phi), std::sin(phi));
        glm::dvec3 h = k25::fromPrior(x, px.alpha, c.ndf);
        double pdf = k25::priorJacobian(h, px.alpha, c.ndf) / (0.25 * 3.14159265358979);
        double v = glm::dot(k25::filteredNdf(params, px, c.ndf, h), glm::dvec3(1.0 / 3.0)) * h.z / pdf;
        sumSmooth += v;
        sumSqSmooth += v * v;
    }
    double mcSmooth = sumSmooth / n;
    double stdErrSmooth = std::sqrt(std::max(sumSqSmooth / n - mcSmooth * mcSmooth, 0.0) / n);
    std::printf("[%s] standard error with the glint sampler %.5f, with smooth-NDF sampling %.5f\n", c.label, stdErr,
                stdErrSmooth);
    EXPECT_LT(stdErr, stdErrSmooth) << c.label;
}

}  // namespace

TEST(Kemppinen2025, ImportanceSamplingGgx) { runSamplingCase({"ggx", 0, 0.3, 0.03, 2e-3}); }
TEST(Kemppinen2025, ImportanceSamplingBeckmann) { runSamplingCase({"beckmann", 1, 0.3, 0.03, 2e-3}); }
