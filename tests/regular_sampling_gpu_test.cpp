// Issue 7 through the real GL pipeline (offscreen llvmpipe): the IBL modes regular, fis and reference against the
// CPU estimators of engine/environment/ibl/ibl_estimators.h under a constant environment (where the lookups are exact, so the
// whole per-pixel chain - frame, pattern buffers, BRDF, pdf, sums - is checked), pattern re-upload on parameter
// changes, and the error of regular vs fis against the accumulated reference under an environment of small bright
// spots (the paper's Figures 8-10; the table is written to test-output/regular_sampling/rmse_table.md).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "core/files.h"
#include "core/image_io.h"
#include "environment/ibl/ibl_estimators.h"
#include "environment/ibl/kurt_ibl_resources.h"
#include "offscreen/offscreen.h"
#include "platform/context.h"
#include "render/aov.h"
#include "render/renderer_capture.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "support/measure.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(RegularSamplingGpu, GlContext);

namespace glimmer {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

fs::path outputDir() {
    fs::path dir = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "regular_sampling";
    fs::create_directories(dir);
    return dir;
}

RenderRequest sphereRequest(const std::string& ibl, int size, const std::string& environment) {
    RenderRequest r;
    r.scene = "sphere";
    r.width = r.height = size;
    r.environment = environment;
    r.settings.ibl = ibl;
    r.settings.apply("light.intensity=0");     // environment only
    r.settings.apply("material.metallic=1");   // no diffuse term
    r.settings.apply("ibl.r0=1");              // Fresnel off, as in the paper's Sec. 8 evaluation
    r.settings.apply("ibl.shadow_alpha=0");
    return r;
}

struct PixelFrame {
    bool valid = false;
    glm::dvec3 wo;   // shading frame
};

// Shading-frame view direction per pixel, rebuilt from the normal and tangent AOVs and the camera ray.
std::vector<PixelFrame> pixelFrames(OffscreenSession& session, RenderRequest r) {
    r.settings.debugView = findAov("normal").viewId;
    RenderResult normals = session.render(r);
    r.settings.debugView = findAov("tangent").viewId;
    RenderResult tangents = session.render(r);
    const Camera& camera = session.scene().cameras.front();
    std::vector<PixelFrame> frames(size_t(r.width) * r.height);
    for (int y = 0; y < r.height; ++y)
        for (int x = 0; x < r.width; ++x) {
            size_t i = size_t(y) * r.width + x;
            if (normals.hdr[i * 4 + 3] <= 0.0f) continue;
            glm::dvec3 n = glm::normalize(glm::dvec3(normals.hdr[i * 4], normals.hdr[i * 4 + 1], normals.hdr[i * 4 + 2]));
            glm::dvec3 t(tangents.hdr[i * 4], tangents.hdr[i * 4 + 1], tangents.hdr[i * 4 + 2]);
            t = glm::normalize(t - n * glm::dot(n, t));
            glm::dvec3 b = glm::cross(n, t);
            Ray ray = cameraRay(camera, r.width, r.height, x + 0.5, y + 0.5);
            glm::dvec3 toEye = -ray.direction;
            glm::dvec3 wo{glm::dot(toEye, t), glm::dot(toEye, b), glm::dot(toEye, n)};
            if (wo.z < 0.3) continue;   // stay away from the silhouette, where G-buffer interpolation dominates
            frames[i] = {true, wo};
        }
    return frames;
}

glm::dvec3 unitSky(glm::dvec3, double) { return glm::dvec3(1.0); }

TEST(RegularSamplingGpu, ModesMatchTheCpuEstimatorsUnderAConstantEnvironment) {
    const int size = 48;
    for (const char* ibl : {"regular", "fis", "reference"}) {
        SCOPED_TRACE(ibl);
        RenderRequest r = sphereRequest(ibl, size, "constant:1,1,1");
        r.settings.apply("ibl.mx=0.2");
        r.settings.apply("ibl.my=0.075");
        r.settings.apply(std::string("ibl.samples=") + (std::string(ibl) == "reference" ? "64" : "17"));
        if (std::string(ibl) == "reference") r.spp = 16;
        OffscreenSession session(r);
        RenderResult result = session.render(r);
        std::vector<PixelFrame> frames = pixelFrames(session, r);
        ibl::KurtLobe lobe{1.0, 1.0, 0.2, 0.075, 0.0};
        ibl::RegularPattern pattern = ibl::selectPatternForBudget(0.2, 0.075, 0.2, 17);
        int checked = 0;
        double worst = 0.0, meanError = 0.0;
        for (size_t i = 0; i < frames.size(); ++i) {
            if (!frames[i].valid) continue;
            glm::dvec3 wo = frames[i].wo;
            glm::dvec3 expected;
            if (std::string(ibl) == "regular") expected = ibl::regularLobe(wo, lobe, pattern, unitSky, 256, 0.0);
            else if (std::string(ibl) == "fis") expected = ibl::fisLobe(wo, lobe, 17, {0.0, 0.0}, unitSky, 256, 0.0);
            else expected = ibl::quadratureLobe(wo, lobe, unitSky, 200, 100);
            double got = result.hdr[i * 4];
            double e = std::abs(got - expected.x) / expected.x;
            worst = std::max(worst, e);
            meanError += e;
            ++checked;
        }
        EXPECT_GT(checked, size * size / 4);
        meanError /= checked;
        std::printf("%s: mean relative error %.5f, worst %.5f over %d pixels\n", ibl, meanError, worst, checked);
        // Float GPU vs double CPU with G-buffer normals and tangents (16-bit targets); the reference is Monte
        // Carlo (1024 samples per pixel) against quadrature, so its bound is statistical.
        if (std::string(ibl) == "reference") {
            EXPECT_LT(meanError, 0.01);
            EXPECT_LT(worst, 0.08);
        } else {
            EXPECT_LT(meanError, 0.003);
            EXPECT_LT(worst, 0.03);
        }
    }
}

TEST(RegularSamplingGpu, PatternsAreRebuiltOnlyWhenParametersChange) {
    auto context = createHeadlessContext(Backend::Egl);
    std::vector<ParamSpec> specs = ibl::kurtMaterialParams();
    specs.push_back({"samples", 14.0f, 1.0f, 512.0f, "", {}, true});
    specs.push_back({"xi0", 0.2f, 0.001f, 0.9f, ""});
    ibl::KurtIblResources resources(specs, true);
    RendererCapture capture(defaultShaderDir());   // unused: no per-object maps here
    Scene scene;
    scene.materials.resize(2);
    scene.materials[0].alpha = 0.1f;
    scene.materials[1].alpha = 0.3f;
    ParamValues values;
    resources.prepare(values, scene, 0, capture);
    resources.prepare(values, scene, 0, capture);
    EXPECT_EQ(resources.uploads(), 1);
    values["samples"] = 30.0f;
    resources.prepare(values, scene, 0, capture);
    EXPECT_EQ(resources.uploads(), 2);
    scene.materials[1].alpha = 0.2f;   // a material edit
    resources.prepare(values, scene, 0, capture);
    EXPECT_EQ(resources.uploads(), 3);
    // Per material: each material's lobe takes its own roughness unless ibl.mx / ibl.my override it.
    auto a = ibl::kurtLobesForMaterial(scene.materials[0], specs, values, 30, 0.2);
    auto b = ibl::kurtLobesForMaterial(scene.materials[1], specs, values, 30, 0.2);
    EXPECT_DOUBLE_EQ(a[0].lobe.mx, 0.1f);
    EXPECT_DOUBLE_EQ(b[0].lobe.mx, 0.2f);
    EXPECT_NE(a[0].pattern.thetaMax, b[0].pattern.thetaMax);
    values["mx"] = 0.25f;
    values["lobe2_ks"] = 0.5f;
    auto c = ibl::kurtLobesForMaterial(scene.materials[0], specs, values, 30, 0.2);
    ASSERT_EQ(c.size(), 2u);
    EXPECT_DOUBLE_EQ(c[0].lobe.mx, 0.25f);
    EXPECT_DOUBLE_EQ(c[0].lobe.my, 0.1f);
    EXPECT_DOUBLE_EQ(c[1].lobe.ks, 0.5f);

    // ibl.pyramid: the environment copy is re-filtered when the filter or the environment changes, not otherwise.
    specs.push_back({"pyramid", 0.0f, 0.0f, 3.0f, "", {"source", "box", "gauss4", "gauss6"}});
    ibl::KurtIblResources filtered(specs, true);
    gl::Texture source = ibl::createPyramidCube(16, GL_RGBA32F);
    const float grey[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    glClearTexImage(source.id(), 0, GL_RGBA, GL_FLOAT, grey);
    filtered.prepare(values, scene, source.id(), capture);
    EXPECT_EQ(filtered.pyramidBuilds(), 0) << "pyramid=source reads the environment's own chain";
    values["pyramid"] = 3.0f;
    filtered.prepare(values, scene, source.id(), capture);
    filtered.prepare(values, scene, source.id(), capture);
    EXPECT_EQ(filtered.pyramidBuilds(), 1);
    values["pyramid"] = 1.0f;
    filtered.prepare(values, scene, source.id(), capture);
    EXPECT_EQ(filtered.pyramidBuilds(), 2);
    const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glClearTexImage(source.id(), 0, GL_RGBA, GL_FLOAT, white);   // the environment changed in place
    filtered.prepare(values, scene, source.id(), capture);
    EXPECT_EQ(filtered.pyramidBuilds(), 3);
}

// Equirectangular HDR sky: dim gradient plus small bright discs (2-10 degrees, intensity ratios up to 1:3000),
// the kind of environment of the paper's Sec. 8 evaluation.
fs::path writeSpotEnvironment() {
    const int w = 1024, h = 512;
    std::vector<float> pixels(size_t(w) * h * 3);
    struct Spot { glm::dvec3 dir; double radiusDeg; double intensity; };
    std::vector<Spot> spots;
    const double spec[][4] = {{0.2, 0.9, 0.4, 2.0},  {-0.5, 0.6, 0.6, 4.0}, {0.7, 0.3, 0.6, 6.0},
                              {-0.1, 0.2, 1.0, 3.0}, {0.4, 0.5, 0.8, 10.0}, {-0.8, 0.1, 0.3, 5.0},
                              {0.0, 0.7, 0.7, 2.5},  {0.6, -0.1, 0.8, 8.0}, {-0.4, -0.2, 0.9, 3.5}};
    const double intensities[] = {300.0, 60.0, 20.0, 150.0, 8.0, 30.0, 100.0, 12.0, 50.0};
    for (int i = 0; i < 9; ++i)
        spots.push_back({glm::normalize(glm::dvec3(spec[i][0], spec[i][1], spec[i][2])), spec[i][3], intensities[i]});
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            // Same mapping as the engine (envref::equirectToDirection): u = 0.5 at -z growing towards +x, v = 0 up.
            double u = (x + 0.5) / w, v = (y + 0.5) / h;
            double theta = v * kPi, phi = (u - 0.5) * 2.0 * kPi;
            glm::dvec3 d{std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
            glm::dvec3 c = glm::dvec3(0.1) + 0.05 * glm::dvec3(d.y, 0.5 * d.y, 0.0);
            for (const Spot& s : spots)
                if (std::acos(std::clamp(glm::dot(d, s.dir), -1.0, 1.0)) < 0.5 * s.radiusDeg * kPi / 180.0)
                    c += glm::dvec3(s.intensity);
            for (int k = 0; k < 3; ++k) pixels[(size_t(y) * w + x) * 3 + k] = float(c[k]);
        }
    fs::path path = outputDir() / "spots.exr";
    auto out = OIIO::ImageOutput::create(path.string());
    OIIO::ImageSpec imageSpec(w, h, 3, OIIO::TypeDesc::FLOAT);
    out->open(path.string(), imageSpec);
    out->write_image(OIIO::TypeDesc::FLOAT, pixels.data());
    out->close();
    return path;
}

double rmse(const RenderResult& a, const RenderResult& b) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i + 3 < a.hdr.size(); i += 4) {
        if (b.hdr[i + 3] <= 0.0f) continue;   // background
        for (int k = 0; k < 3; ++k) {
            double d = double(a.hdr[i + k]) - double(b.hdr[i + k]);
            sum += d * d;
        }
        n += 3;
    }
    return std::sqrt(sum / double(n));
}

// The paper tunes the MIP bias of each method for the lowest error (Sec. 8, Fig. 9): the lowest RMSE over a grid.
double bestBias(OffscreenSession& session, RenderRequest r, const RenderResult& reference, double& bias) {
    double best = 1e30;
    for (double b : {-1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0}) {
        r.settings.apply("ibl.mip_bias=" + std::to_string(b));
        double e = rmse(session.render(r), reference);
        if (e < best) { best = e; bias = b; }
    }
    return best;
}

// Asserted: the Gaussian 6x6 comparison at the paper's count and the convergence of both estimators at bias 0.
// The table's other columns (the best MIP bias of every row, 7 renders each, and the gauss6 pyramid at the two
// larger budgets) are measurements that nothing asserts: rendered with GLIMMER_MEASURE=1 only (nan otherwise).
// Each material costs about 23 s (its 16384-sample reference at 128x128, then 8 renders). CI: the anisotropic
// material (the Fig. 8 pattern's rejection and the anisotropic pdf); GLIMMER_MEASURE=1 adds the isotropic one.
TEST(RegularSamplingGpu, ErrorAgainstTheReferenceUnderSmallBrightSpots) {
    if (!test::fullMeasurement()) GTEST_SKIP() << "GLIMMER_MEASURE=1 runs it (33 s); CI: ModesMatchTheCpuEstimatorsUnderAConstantEnvironment";
    const fs::path env = writeSpotEnvironment();
    const int size = 128;
    const bool measure = test::fullMeasurement();
    const double unmeasured = std::nan("");
    struct Material { const char* name; double mx, my; int paperSamples; };
    std::vector<Material> materials = {{"anisotropic", 0.2, 0.075, 17}};
    if (measure) materials.insert(materials.begin(), Material{"isotropic", 0.1, 0.1, 14});
    FILE* table = std::fopen((outputDir() / "rmse_table.md").string().c_str(), "w");
    std::fprintf(table, "| material | budget | xi0 | samples | regular | fis | regular, best bias | fis, best bias "
                        "| regular gauss6 | fis gauss6 | regular gauss6, best bias | fis gauss6, best bias |\n"
                        "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const Material& m : materials) {
        SCOPED_TRACE(m.name);
        auto setMaterial = [&](RenderRequest& r) {
            r.settings.apply("ibl.mx=" + std::to_string(m.mx));
            r.settings.apply("ibl.my=" + std::to_string(m.my));
        };
        RenderRequest ref = sphereRequest("reference", size, env.string());
        setMaterial(ref);
        ref.settings.apply("ibl.samples=64");
        ref.spp = 256;   // 16384 samples per pixel
        RenderResult reference = OffscreenSession(ref).render(ref);
        writeExr(outputDir() / (std::string("reference_") + m.name + ".exr"), reference.hdr.data(), reference.width,
                 reference.height);

        // Budgets: the paper's count for this material (Fig. 8, xi0 = 0.2), then 30 (xi0 = 0.1) and 270
        // (xi0 = 0.01) as in Fig. 9-10. FIS gets exactly the regular pattern's sample count. One session per mode
        // at a time (sessions own their GL context).
        const std::pair<int, double> budgets[] = {{m.paperSamples, 0.2}, {30, 0.1}, {270, 0.01}};
        double regularErrors[3], fisErrors[3], regularBest[3], fisBest[3], regularBias[3], fisBias[3];
        double regularGauss6[3], fisGauss6[3], regularGauss6Best[3], fisGauss6Best[3], regularGauss6Bias[3],
            fisGauss6Bias[3];
        for (double* column : {regularBest, fisBest, regularBias, fisBias, regularGauss6, fisGauss6, regularGauss6Best,
                               fisGauss6Best, regularGauss6Bias, fisGauss6Bias})
            std::fill(column, column + 3, unmeasured);
        int counts[3];
        {
            RenderRequest reg = sphereRequest("regular", size, env.string());
            setMaterial(reg);
            OffscreenSession session(reg);
            for (int b = 0; b < 3; ++b) {
                auto [budget, xi0] = budgets[b];
                counts[b] = ibl::selectPatternForBudget(m.mx, m.my, xi0, budget).size();
                reg.settings.apply("ibl.samples=" + std::to_string(budget));
                reg.settings.apply("ibl.xi0=" + std::to_string(xi0));
                reg.settings.apply("ibl.mip_bias=0");
                RenderResult regular = session.render(reg);
                regularErrors[b] = rmse(regular, reference);
                if (measure) regularBest[b] = bestBias(session, reg, reference, regularBias[b]);
                if (b == 0 || measure) {
                    reg.settings.apply("ibl.pyramid=gauss6");   // the paper's Sec. 8 pyramid
                    reg.settings.apply("ibl.mip_bias=0");
                    RenderResult regularGauss = session.render(reg);
                    regularGauss6[b] = rmse(regularGauss, reference);
                    if (measure) regularGauss6Best[b] = bestBias(session, reg, reference, regularGauss6Bias[b]);
                    reg.settings.apply("ibl.pyramid=source");
                    writeExr(outputDir() / ("regular_gauss6_" + std::string(m.name) + "_" + std::to_string(budget) + ".exr"),
                             regularGauss.hdr.data(), regularGauss.width, regularGauss.height);
                }
                writeExr(outputDir() / ("regular_" + std::string(m.name) + "_" + std::to_string(budget) + ".exr"),
                         regular.hdr.data(), regular.width, regular.height);
            }
        }
        {
            RenderRequest fis = sphereRequest("fis", size, env.string());
            setMaterial(fis);
            OffscreenSession session(fis);
            for (int b = 0; b < 3; ++b) {
                fis.settings.apply("ibl.samples=" + std::to_string(counts[b]));
                fis.settings.apply("ibl.mip_bias=0");
                RenderResult importance = session.render(fis);
                fisErrors[b] = rmse(importance, reference);
                if (measure) fisBest[b] = bestBias(session, fis, reference, fisBias[b]);
                if (b == 0 || measure) {
                    fis.settings.apply("ibl.pyramid=gauss6");
                    fis.settings.apply("ibl.mip_bias=0");
                    RenderResult fisGauss = session.render(fis);
                    fisGauss6[b] = rmse(fisGauss, reference);
                    if (measure) fisGauss6Best[b] = bestBias(session, fis, reference, fisGauss6Bias[b]);
                    fis.settings.apply("ibl.pyramid=source");
                    writeExr(outputDir() / ("fis_gauss6_" + std::string(m.name) + "_" + std::to_string(budgets[b].first) + ".exr"),
                             fisGauss.hdr.data(), fisGauss.width, fisGauss.height);
                }
                writeExr(outputDir() / ("fis_" + std::string(m.name) + "_" + std::to_string(budgets[b].first) + ".exr"),
                         importance.hdr.data(), importance.width, importance.height);
            }
        }
        for (int b = 0; b < 3; ++b) {
            std::fprintf(table, "| %s (mx=%.3g, my=%.3g) | %d | %.3g | %d | %.4f | %.4f | %.4f (%+.1f) | %.4f (%+.1f) "
                                "| %.4f | %.4f | %.4f (%+.1f) | %.4f (%+.1f) |\n",
                         m.name, m.mx, m.my, budgets[b].first, budgets[b].second, counts[b], regularErrors[b],
                         fisErrors[b], regularBest[b], regularBias[b], fisBest[b], fisBias[b], regularGauss6[b],
                         fisGauss6[b], regularGauss6Best[b], regularGauss6Bias[b], fisGauss6Best[b], fisGauss6Bias[b]);
            std::printf("%s budget %d xi0 %.3g: %d samples, RMSE regular %.4f fis %.4f; best bias: regular %.4f (%+.1f) "
                        "fis %.4f (%+.1f)\n", m.name, budgets[b].first, budgets[b].second, counts[b], regularErrors[b],
                        fisErrors[b], regularBest[b], regularBias[b], fisBest[b], fisBias[b]);
            std::printf("    gauss6 pyramid: regular %.4f fis %.4f; best bias: regular %.4f (%+.1f) fis %.4f (%+.1f)\n",
                        regularGauss6[b], fisGauss6[b], regularGauss6Best[b], regularGauss6Bias[b], fisGauss6Best[b],
                        fisGauss6Bias[b]);
        }
        // The paper's setting (Sec. 8: Gaussian 6x6 pyramid for both methods, no MIP bias): regular has the lower
        // RMSE at the paper's sample count. With the environment's box chain, or with each method's best MIP bias,
        // it does not (measured in rmse_table.md, see docs/regular_sampling.md).
        EXPECT_LT(regularGauss6[0], fisGauss6[0]) << "regular vs fis at the paper's count, Gaussian 6x6 pyramid";
        // Both estimators approach the reference as samples grow (Fig. 9-10).
        EXPECT_LT(regularErrors[1], regularErrors[0]);
        EXPECT_LT(regularErrors[2], regularErrors[1]);
        EXPECT_LT(fisErrors[1], fisErrors[0]) << "fis must approach the reference as samples grow";
        EXPECT_LT(fisErrors[2], fisErrors[1]) << "fis must approach the reference as samples grow";
    }
    std::fclose(table);
}

}  // namespace
}  // namespace glimmer
