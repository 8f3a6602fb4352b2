// Tests of image-based lighting with the kemppinen2025 glint sampler (issue 5): the IBL modes `glint-is` (half
// vectors from the filtered glinty NDF, Kemppinen et al. 2025 Sec. 3.3.5 / Algorithm 2) and `ndf-is` (the smooth
// NDF, the comparison of the paper's Fig. 7).
// 1. The CPU reference estimator (engine/render/ibl_sampling_reference) is unbiased: its Monte Carlo mean equals
//    quadrature of the same reflection integral.
// 2. The shader's iblRadiance (run by a compute shader, the code the lighting pass includes) equals the CPU
//    estimator sample by sample (same random streams), so the GPU estimator inherits 1.
// 3. Fig. 7 on a glinty sphere through the real renderer: RMSE against a high-spp reference falls like
//    1/sqrt(spp), and glint-is has a lower RMSE than ndf-is at equal spp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "common/bindings.glsl"
#include "core/clock.h"
#include "core/error.h"
#include "core/files.h"
#include "environment/environment.h"
#include "environment/ibl/ibl_modes.h"
#include "gl/handles.h"
#include "gl/program.h"
#include "glints/methods.h"
#include "platform/context.h"
#include "reference/environment_reference.h"
#include "reference/ibl_sampling_reference.h"
#include "reference/kemppinen2025_reference.h"
#include "render/aov.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "render/settings.h"
#include "render/shader_interface.h"
#include "scene/builtin_scenes.h"
#include "support/measure.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(Kemppinen2025Ibl, GlContext);

using namespace glimmer;
namespace k25 = glimmer::kemppinen2025;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A smooth, direction-dependent environment the CPU can evaluate exactly (sky brighter above, warm towards +x).
glm::dvec3 analyticSky(const glm::dvec3& d) {
    return glm::dvec3(1.0 + 0.6 * d.y + 0.3 * d.x, 0.9 + 0.5 * d.y, 0.8 + 0.7 * d.y * d.y);
}

// A shading frame tilted away from the world axes (so world and shading directions differ).
glm::dmat3 tiltedFrame() {
    glm::dvec3 n = glm::normalize(glm::dvec3(0.2, 0.9, 0.35));
    glm::dvec3 t = glm::normalize(glm::cross(glm::dvec3(0.0, 0.0, 1.0), n));
    glm::dvec3 b = glm::cross(n, t);
    return glm::dmat3(t, b, n);
}

struct EstimatorCase {
    const char* label;
    int ndf;
    double alpha, micro, footprint;
};

k25::Params caseParams(const EstimatorCase& c) {
    k25::Params p;
    p.microRoughness = c.micro;
    p.density = 2e6;
    return p;
}

k25::Surface caseSurface(const EstimatorCase& c) {
    k25::Surface s;
    s.uv = {31.3, 17.8};
    s.duvdx = {c.footprint, 0.0};
    s.duvdy = {0.0, c.footprint * 0.8};
    s.alpha = c.alpha;
    s.ndf = c.ndf;
    return s;
}

iblref::ShadingPoint caseShading(const EstimatorCase& c) {
    iblref::ShadingPoint p;
    p.frame = tiltedFrame();
    p.wo = glm::normalize(glm::dvec3(0.35, -0.2, 0.9));   // ~26 degrees off the normal
    p.alpha = c.alpha;
    p.ndf = c.ndf;
    p.f0 = {0.95, 0.64, 0.54};
    return p;
}

}  // namespace

// 1. The estimator is unbiased: the mean of 2^16 CPU estimates (glint-is and ndf-is) equals quadrature of
// int f_spec cos L over half vectors (prior-space midpoints, 512^2) within 4 standard errors + 0.5% (quadrature
// error). The glinty NDF of a pixel with a few dozen visible glints is a sum of narrow lobes: a wrong pdf,
// Jacobian (4 |wo.h|) or weight shifts the mean by far more.
TEST(Kemppinen2025Ibl, CpuEstimatorMatchesQuadrature) {
    for (const EstimatorCase& c : {EstimatorCase{"ggx", k25::kGgx, 0.3, 0.03, 2e-3},
                                   EstimatorCase{"beckmann", k25::kBeckmann, 0.3, 0.03, 2e-3}}) {
        k25::Params params = caseParams(c);
        k25::Surface surface = caseSurface(c);
        k25::PixelSetup setup = k25::setupPixel(params, surface);
        iblref::ShadingPoint p = caseShading(c);
        iblref::NdfFn glintNdf = [&](const glm::dvec3& h) { return k25::filteredNdf(params, setup, c.ndf, h); };
        iblref::GlintPixel glint{&params, &setup};
        glm::dvec3 quad = iblref::specularIntegral(p, glintNdf, analyticSky, 512);
        const uint32_t n = 1u << 16;
        for (iblref::Mode mode : {iblref::Mode::GlintIs, iblref::Mode::NdfIs}) {
            glm::dvec3 sum(0.0), sumSq(0.0);
            for (uint32_t i = 0; i < n; ++i) {
                glm::dvec3 v = iblref::estimate(mode, p, true, glintNdf, glint, {7, 9}, i, 0u, analyticSky);
                sum += v;
                sumSq += v * v;
            }
            glm::dvec3 mean = sum / double(n);
            glm::dvec3 stdErr = glm::sqrt(glm::max(sumSq / double(n) - mean * mean, glm::dvec3(0.0)) / double(n));
            const char* name = mode == iblref::Mode::GlintIs ? "glint-is" : "ndf-is";
            std::printf("[%s %s] Monte Carlo (%.5f %.5f %.5f) +- (%.5f %.5f %.5f) vs quadrature (%.5f %.5f %.5f)\n",
                        c.label, name, mean.x, mean.y, mean.z, stdErr.x, stdErr.y, stdErr.z, quad.x, quad.y, quad.z);
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(mean[k], quad[k], 4.0 * stdErr[k] + 0.005 * quad[k]) << c.label << " " << name << " " << k;
        }
    }
}

namespace {

// The compute shader shaders/environment/ibl/ibl_estimator_test.glsl with the method and mode of `settings`.
class EstimatorRig {
public:
    EstimatorRig() : context_(createHeadlessContext(Backend::Egl)), env_(defaultShaderDir()) {
        // The procedural sky whose sun is carried by a directional light: a smooth map (no sun disk), so float and
        // double directions a hair apart read the same radiance.
        SunDescription sun;
        sun.analytic = true;
        env_.update("procedural", sun, "--env");
        source_ = readSource();
    }
    ~EstimatorRig() { context_->makeCurrent(); }

    // Radiance of the bound map as the shader's envRadiance(d, 0) reads it (CPU bilinear, intensity 1, no rotation).
    glm::dvec3 radiance(const glm::dvec3& worldDirection) const {
        return glm::dvec3(envref::sampleCube(source_, glm::vec3(worldDirection)));
    }

    std::vector<glm::vec4> run(const std::string& iblMode, const EstimatorCase& c, const iblref::ShadingPoint& p,
                               bool glinty, glm::ivec2 pixel, uint32_t count) {
        const GlintMethod& method = findGlintMethod("kemppinen2025");
        const IblMode& mode = findIblMode(iblMode);
        ParamValues methodValues{{"micro_roughness", float(c.micro)}, {"density", 2e6f}};
        gl::ProgramDesc desc;
        desc.name = "ibl estimator test/" + iblMode;
        desc.stages = {{GL_COMPUTE_SHADER, "environment/ibl/ibl_estimator_test.glsl"}};
        desc.defines = {method.define, mode.define};
        desc.preamble = methodParamsGlsl(method) + iblParamsGlsl(mode);
        desc.includeMacros["GLINT_METHOD_FILE"] = method.shaderFile;
        desc.includeMacros["IBL_MODE_FILE"] = mode.shaderFile;
        gl::Program program(defaultShaderDir(), desc);
        std::vector<float> packed = packMethodParams(method, methodValues);
        gl::Buffer methodBuffer = gl::createBuffer(GLsizeiptr(packed.size() * sizeof(float)), packed.data());
        std::vector<float> iblPacked = packIblParams(mode, {});
        gl::Buffer iblBuffer = gl::createBuffer(GLsizeiptr(iblPacked.size() * sizeof(float)), iblPacked.data());
        gl::Buffer frameBuffer = gl::createBuffer(1024, nullptr);
        gl::Buffer out = gl::createBuffer(GLsizeiptr(count) * 16, nullptr);
        program.use();
        glUniform2f(0, 31.3f, 17.8f);
        glUniform4f(1, float(c.footprint), 0.0f, 0.0f, float(c.footprint * 0.8));
        glUniform1f(2, float(c.alpha));
        glUniform1i(3, c.ndf);
        glUniform1ui(4, count);
        glUniform2i(5, pixel.x, pixel.y);
        glm::mat3 frame(p.frame);
        glUniformMatrix3fv(6, 1, GL_FALSE, &frame[0][0]);
        glm::vec3 toEye(p.frame * p.wo);
        glUniform3f(9, toEye.x, toEye.y, toEye.z);
        glUniform3f(10, float(p.f0.x), float(p.f0.y), float(p.f0.z));
        glUniform3f(11, float(p.diffuseAlbedo.x), float(p.diffuseAlbedo.y), float(p.diffuseAlbedo.z));
        glUniform1i(12, glinty ? 1 : 0);
        glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_FRAME, frameBuffer.id());
        glBindBufferBase(GL_UNIFORM_BUFFER, kMethodParamBinding, methodBuffer.id());
        glBindBufferBase(GL_UNIFORM_BUFFER, kIblParamBinding, iblBuffer.id());
        env_.bind(1.0f, 0.0f);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_RIG_OUTPUT, out.id());
        glDispatchCompute((count + 63) / 64, 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<glm::vec4> result(count);
        glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(count) * 16, result.data());
        return result;
    }

private:
    envref::CubeImage readSource() {
        int size = Environment::kFaceSize;
        envref::CubeImage cube;
        cube.size = size;
        cube.rgba.resize(size_t(6) * size * size * 4);
        glGetTextureImage(env_.sourceCube(), 0, GL_RGBA, GL_FLOAT, GLsizei(cube.rgba.size() * sizeof(float)),
                          cube.rgba.data());
        return cube;
    }

    std::unique_ptr<GLContext> context_;
    Environment env_;
    envref::CubeImage source_;
};

}  // namespace

// 2. The shader's iblRadiance equals the CPU estimator sample by sample: same pixel, same sample indices, same
// random streams, the environment read back from the GPU's source cube. Per sample the two agree within 1% (of
// the value, or 1% of the mean for near-zero samples) except where float and double take different branches
// (the reservoir's comparison, a sample on the disk's rim): at most 1% of the samples (measured: 0-1 of 4096);
// the means agree within 0.5%. A wrong seed, Jacobian, Fresnel angle, frame or environment direction disagrees on
// nearly every sample (an argument-order slip in the CPU sampler's random draws made 40-70% differ).
TEST(Kemppinen2025Ibl, ShaderEstimatorMatchesCpuSampleBySample) {
    EstimatorRig rig;
    const uint32_t n = 4096;
    struct Case {
        const char* mode;
        EstimatorCase c;
        bool glinty;
        bool dielectric;
    };
    for (const Case& tc : {Case{"glint-is", {"ggx", k25::kGgx, 0.3, 0.03, 2e-3}, true, false},
                           Case{"glint-is", {"beckmann", k25::kBeckmann, 0.3, 0.01, 2e-3}, true, false},
                           Case{"ndf-is", {"ggx", k25::kGgx, 0.3, 0.03, 2e-3}, true, false},
                           Case{"ndf-is", {"beckmann", k25::kBeckmann, 0.5, 0.03, 2e-3}, false, true},
                           Case{"glint-is", {"ggx smooth material", k25::kGgx, 0.2, 0.03, 2e-3}, false, true}}) {
        const EstimatorCase& c = tc.c;
        k25::Params params = caseParams(c);
        k25::Surface surface = caseSurface(c);
        k25::PixelSetup setup = k25::setupPixel(params, surface);
        iblref::ShadingPoint p = caseShading(c);
        if (tc.dielectric) {
            p.f0 = glm::dvec3(0.04);
            p.diffuseAlbedo = {0.5, 0.3, 0.2};
        }
        iblref::NdfFn glintNdf = [&](const glm::dvec3& h) { return k25::filteredNdf(params, setup, c.ndf, h); };
        iblref::GlintPixel glint{&params, &setup};
        const glm::ivec2 pixel(37, 113);
        std::vector<glm::vec4> gpu = rig.run(tc.mode, c, p, tc.glinty, pixel, n);
        iblref::Mode mode = std::string(tc.mode) == "glint-is" ? iblref::Mode::GlintIs : iblref::Mode::NdfIs;
        auto env = [&](const glm::dvec3& d) { return rig.radiance(d); };
        std::vector<glm::dvec3> cpu(n);
        glm::dvec3 meanGpu(0.0), meanCpu(0.0);
        for (uint32_t i = 0; i < n; ++i) {
            cpu[i] = iblref::estimate(mode, p, tc.glinty, glintNdf, glint, pixel, i, 0u, env);
            meanGpu += glm::dvec3(gpu[i]) / double(n);
            meanCpu += cpu[i] / double(n);
        }
        int mismatched = 0, nonZero = 0;
        double scale = std::max({meanCpu.x, meanCpu.y, meanCpu.z});
        for (uint32_t i = 0; i < n; ++i) {
            glm::dvec3 g(gpu[i]);
            if (cpu[i] != glm::dvec3(0.0)) ++nonZero;
            for (int k = 0; k < 3; ++k)
                if (std::abs(g[k] - cpu[i][k]) > 0.01 * std::max(std::abs(cpu[i][k]), scale)) {
                    ++mismatched;
                    break;
                }
        }
        std::printf("[%s %s] %d of %u samples differ by > 1%% (%d non-zero); mean GPU (%.5f %.5f %.5f) CPU (%.5f "
                    "%.5f %.5f)\n", tc.mode, c.label, mismatched, n, nonZero, meanGpu.x, meanGpu.y, meanGpu.z,
                    meanCpu.x, meanCpu.y, meanCpu.z);
        EXPECT_GT(nonZero, int(n / 2)) << tc.mode << " " << c.label;
        EXPECT_LE(mismatched, int(n * 0.01)) << tc.mode << " " << c.label;
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(meanGpu[k], meanCpu[k], 0.005 * scale) << tc.mode << " " << c.label;
    }
}

// glint-is runs only with the method whose sampler it uses: a one-line usage error naming the flag otherwise.
TEST(Kemppinen2025Ibl, GlintIsNeedsKemppinen2025) {
    EXPECT_THROW(checkIblModeMethod(findIblMode("glint-is"), "smooth"), UsageError);
    EXPECT_NO_THROW(checkIblModeMethod(findIblMode("glint-is"), "kemppinen2025"));
    for (const char* method : {"smooth", "deliot2023", "zirr2016", "kemppinen2025"})
        EXPECT_NO_THROW(checkIblModeMethod(findIblMode("ndf-is"), method)) << method;
    std::string out = test::makeTempDir("kibl") + "/x.png";
    test::ProcessResult r = test::runGlimmer({"render", "--scene", "sphere", "--method", "deliot2023", "--ibl",
                                              "glint-is", "--size", "16x16", "--out", out});
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--ibl glint-is"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("kemppinen2025"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

namespace {

// The glinty sphere (built-in scene `sphere`, a metal of roughness 0.3) under an environment, rendered by the real
// renderer with an accumulating IBL mode.
struct SphereLook {
    int ndf = 0;                 // material.ndf
    float density = 3e4f;        // kemppinen2025 density
    float microRoughness = 0.005f;
};

class SphereIblRig {
public:
    explicit SphereIblRig(const std::string& environment) : base_(makeBuiltinScene("sphere")) {
        base_.environment = environment;
        context_ = createHeadlessContext(Backend::Egl);
        scene_ = base_;
        gpuScene_ = std::make_unique<GpuScene>(scene_);
    }
    ~SphereIblRig() {
        context_->makeCurrent();
        renderers_.clear();
        gpuScene_.reset();
    }
    static RenderSettings settingsFor(const SphereLook& look, const std::string& mode, int seed) {
        RenderSettings settings;
        settings.method = "kemppinen2025";
        settings.common["material.ndf"] = float(look.ndf);
        settings.methods["kemppinen2025"]["density"] = look.density;
        settings.methods["kemppinen2025"]["micro_roughness"] = look.microRoughness;
        settings.ibl = mode;
        settings.iblValues[mode]["seed"] = float(seed);
        return settings;
    }
    // Mean of `spp` estimates of `mode` with random-stream offset `seed`: RGBA32F rows, alpha 1 on the sphere.
    // One renderer per mode, so each lighting program is compiled once (the tests run without a shader cache).
    std::vector<float> render(const SphereLook& look, const std::string& mode, int spp, int seed, int size) {
        context_->makeCurrent();
        RenderSettings settings = settingsFor(look, mode, seed);
        scene_ = base_;
        applySceneOverrides(settings, scene_);
        gpuScene_->updateMaterialsAndLights(scene_);
        std::unique_ptr<Renderer>& renderer = renderers_[mode];
        if (!renderer)
            renderer = std::make_unique<Renderer>(defaultShaderDir(), settings);
        else
            renderer->setSettings(settings);
        View view{.camera = scene_.cameras.front(), .width = size, .height = size};
        renderer->renderAccumulated(scene_, *gpuScene_, view, spp);
        glFinish();
        return renderer->readHdr();
    }

private:
    std::unique_ptr<GLContext> context_;
    Scene base_, scene_;
    std::unique_ptr<GpuScene> gpuScene_;
    std::map<std::string, std::unique_ptr<Renderer>> renderers_;
};

// RMSE over the sphere's pixels (alpha > 0.5) and the three channels.
double sphereRmse(const std::vector<float>& image, const std::vector<float>& reference) {
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < reference.size(); i += 4) {
        if (reference[i + 3] < 0.5f) continue;
        for (int k = 0; k < 3; ++k) sum += double(image[i + k] - reference[i + k]) * double(image[i + k] - reference[i + k]);
        count += 3;
    }
    return std::sqrt(sum / double(std::max<size_t>(count, 1)));
}

double sphereMean(const std::vector<float>& image) {
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < image.size(); i += 4) {
        if (image[i + 3] < 0.5f) continue;
        sum += image[i] + image[i + 1] + image[i + 2];
        count += 3;
    }
    return sum / double(std::max<size_t>(count, 1));
}

// Least-squares slope of log(y) against log(x).
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
    double mx = 0, my = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        mx += std::log(x[i]) / double(x.size());
        my += std::log(y[i]) / double(y.size());
    }
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
        sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
    }
    return sxy / sxx;
}

struct ConvergenceResult {
    std::vector<double> spp, rmseGlint, rmseNdf;
    double referenceMean = 0, ndfMean = 0, glintMean = 0;
};

// Renders the reference (glint-is, kReferenceSpp, its own seed) and both modes at 1, 2, 4, ... kMaxSpp spp (each
// with a fresh seed, so the points are independent), and prints the table of the paper's Fig. 7.
ConvergenceResult runConvergence(SphereIblRig& rig, const SphereLook& look, const char* label, int size,
                                 int referenceSpp, int maxSpp) {
    Stopwatch clock;
    std::vector<float> reference = rig.render(look, "glint-is", referenceSpp, 1000, size);
    double referenceMs = clock.elapsedMs();
    ConvergenceResult r;
    r.referenceMean = sphereMean(reference);
    std::printf("[%s] %dx%d, reference: glint-is %d spp (%.0f ms), sphere mean radiance %.4f\n", label, size, size,
                referenceSpp, referenceMs, r.referenceMean);
    std::printf("[%s]  spp | RMSE glint-is | RMSE ndf-is | ndf-is / glint-is\n", label);
    int seed = 1;
    for (int spp = 1; spp <= maxSpp; spp *= 2) {
        std::vector<float> glint = rig.render(look, "glint-is", spp, seed++, size);
        std::vector<float> ndf = rig.render(look, "ndf-is", spp, seed++, size);
        r.spp.push_back(spp);
        r.rmseGlint.push_back(sphereRmse(glint, reference));
        r.rmseNdf.push_back(sphereRmse(ndf, reference));
        std::printf("[%s] %4d | %13.5f | %11.5f | %.2f\n", label, spp, r.rmseGlint.back(), r.rmseNdf.back(),
                    r.rmseNdf.back() / r.rmseGlint.back());
        if (spp == maxSpp) {
            r.glintMean = sphereMean(glint);
            r.ndfMean = sphereMean(ndf);
        }
    }
    std::printf("[%s] total %.0f ms\n", label, clock.elapsedMs());
    return r;
}

void checkConvergence(const ConvergenceResult& r, const char* label) {
    double slopeGlint = logLogSlope(r.spp, r.rmseGlint), slopeNdf = logLogSlope(r.spp, r.rmseNdf);
    std::printf("[%s] log-log slopes: glint-is %.3f, ndf-is %.3f (1/sqrt(spp): -0.5); sphere means at %g spp: "
                "glint-is %.4f, ndf-is %.4f, reference %.4f\n", label, slopeGlint, slopeNdf, r.spp.back(),
                r.glintMean, r.ndfMean, r.referenceMean);
    // Independent unbiased estimators: RMSE^2 = sigma^2 / spp + sigma_ref^2 / spp_ref. With spp <= spp_ref / 16 the
    // second term flattens the slope by < 0.02; a biased mode (one converging to another image) flattens it
    // towards 0. Measured -0.53 (GGX) and -0.50 (Beckmann).
    EXPECT_NEAR(slopeGlint, -0.5, 0.1) << label;
    // ndf-is finds the sharp glints only by chance: rare huge f / pdf values (fireflies) make its empirical RMSE at
    // 8 spp too erratic for a slope tolerance (measured -0.23 GGX, -0.50 Beckmann); its unbiasedness is checked
    // exactly by the two tests above. Here: it falls, and stays well above glint-is (measured 2.8-5.6x).
    EXPECT_LT(slopeNdf, -0.1) << label;
    for (size_t i = 0; i < r.spp.size(); ++i)
        EXPECT_GT(r.rmseNdf[i], 1.5 * r.rmseGlint[i]) << label << " spp " << r.spp[i];
    // Both converge to the reference image (sphere means; 8 spp of a heavy-tailed estimator: 3% and 5%).
    EXPECT_NEAR(r.glintMean / r.referenceMean, 1.0, 0.03) << label;
    EXPECT_NEAR(r.ndfMean / r.referenceMean, 1.0, 0.05) << label;
}

}  // namespace

// 3. The paper's Fig. 7 (GGX and Beckmann) on the procedural HDR sky, which needs no files (its sun is the scene's
// directional light, so the map is smooth and the variance comes from the glints). Sparse, sharp glints
// (density 3e4 per m^2, alpha* 0.005: about 20 glints per pixel footprint, lobes narrower than the angular cells
// at the LOD of this view), where the paper says importance sampling pays ("effectiveness increases with the
// specularity"). 128x128, reference glint-is 128 spp with its own seed, 1..8 spp.
// Each NDF costs about 29 s (158 spp at 128x128). CI: GGX, whose ndf-is slope (measured -0.23) is the nearest to its
// bound; GLIMMER_MEASURE=1 adds Beckmann.
TEST(Kemppinen2025Ibl, ConvergenceOnGlintySphereProceduralSky) {
    SphereIblRig rig("procedural");
    const std::vector<int> ndfs = test::fullMeasurement() ? std::vector<int>{0, 1} : std::vector<int>{0};
    for (int ndf : ndfs) {
        const char* label = ndf == 0 ? "procedural sky, GGX" : "procedural sky, Beckmann";
        SphereLook look;
        look.ndf = ndf;
        checkConvergence(runConvergence(rig, look, label, 128, 128, 8), label);
    }
}

// 4. Through the real renderer (G-buffer, lighting pass, IBL mode file): one glint-is sample per pixel of the
// glinty sphere under a constant environment of radiance 1 (lights at intensity 0) equals the CPU estimator at the
// same pixel and sample index, the surface rebuilt from the G-buffer AOVs (UV, derivatives, normal and tangent as
// stored; the bitangent's handedness and the view direction from the sphere's geometry). At least 97% of the
// covered pixels agree within 1% (measured 1736 of 1756); the rest are float / double branch flips and silhouette
// pixels where the flat triangles and the analytic sphere differ. A mirrored shading frame: 705 of 1756.
TEST(Kemppinen2025Ibl, RenderedSampleMatchesCpuEstimatorPerPixel) {
    const int size = 64;
    SphereLook look;   // sparse sharp glints: a wrong glint, pdf or frame changes the value by far more than 1%
    Scene base = makeBuiltinScene("sphere");
    base.environment = "constant:1,1,1";
    auto context = createHeadlessContext(Backend::Egl);
    RenderSettings settings = SphereIblRig::settingsFor(look, "glint-is", 0);
    settings.common["light.intensity"] = 0.0f;
    Scene scene = base;
    applySceneOverrides(settings, scene);
    auto gpuScene = std::make_unique<GpuScene>(scene);
    auto renderer = std::make_unique<Renderer>(defaultShaderDir(), settings);
    auto view = [&](const char* aov) {
        RenderSettings s = settings;
        s.debugView = findAov(aov).viewId;
        renderer->setSettings(s);
        renderer->renderView(scene, *gpuScene, scene.cameras.front(), size, size);
        glFinish();
        return renderer->readHdr();
    };
    std::vector<float> radiance = view("final"), uv = view("uv"), dx = view("duvdx"), dy = view("duvdy"),
                       normal = view("normal"), tangent = view("tangent");
    renderer.reset();
    gpuScene.reset();

    const Camera& camera = scene.cameras.front();
    glm::dmat4 invVp = glm::inverse(glm::dmat4(camera.projection(1.0f)) * glm::dmat4(camera.view()));
    glm::dvec3 eye(camera.position);
    k25::Params params;
    params.density = look.density;
    params.microRoughness = look.microRoughness;
    const Material& material = scene.materials.front();
    glm::dvec3 f0 = glm::dvec3(material.baseColor);   // metallic 1
    auto constantSky = [](const glm::dvec3&) { return glm::dvec3(1.0); };
    int covered = 0, agree = 0, nonZero = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            size_t i = (size_t(y) * size + x) * 4;
            if (radiance[i + 3] < 0.5f) continue;
            // The pixel's ray hits the unit sphere (the mesh's flat triangles differ by < 3e-4).
            glm::dvec4 p = invVp * glm::dvec4((x + 0.5) / size * 2.0 - 1.0, (y + 0.5) / size * 2.0 - 1.0, 0.5, 1.0);
            glm::dvec3 dir = glm::normalize(glm::dvec3(p) / p.w - eye);
            double b = glm::dot(eye, dir), c = glm::dot(eye, eye) - 1.0, disc = b * b - c;
            if (disc <= 0.0) continue;
            glm::dvec3 position = eye + dir * (-b - std::sqrt(disc));
            ++covered;
            glm::dvec3 n = glm::normalize(glm::dvec3(normal[i], normal[i + 1], normal[i + 2]));
            glm::dvec3 t(tangent[i], tangent[i + 1], tangent[i + 2]);
            t = glm::normalize(t - n * glm::dot(n, t));
            // makeUvSphere: handedness +1 when cross(n, t) follows dP/dtheta.
            glm::dvec3 pn = glm::normalize(position);
            double theta = std::acos(std::clamp(pn.y, -1.0, 1.0)), phi = std::atan2(-pn.z, pn.x);
            glm::dvec3 dPdtheta(std::cos(theta) * std::cos(phi), -std::sin(theta), -std::cos(theta) * std::sin(phi));
            double handedness = glm::dot(glm::cross(n, t), dPdtheta) < 0.0 ? -1.0 : 1.0;
            glm::dvec3 bt = handedness * glm::cross(n, t);
            k25::Surface surface;
            surface.uv = {uv[i], uv[i + 1]};
            surface.duvdx = {dx[i], dx[i + 1]};
            surface.duvdy = {dy[i], dy[i + 1]};
            surface.alpha = material.alpha;
            surface.ndf = look.ndf;
            k25::PixelSetup setup = k25::setupPixel(params, surface);
            iblref::ShadingPoint sp;
            sp.frame = glm::dmat3(t, bt, n);
            sp.wo = glm::transpose(sp.frame) * glm::normalize(eye - position);
            sp.alpha = material.alpha;
            sp.ndf = look.ndf;
            sp.f0 = f0;
            iblref::NdfFn glintNdf = [&](const glm::dvec3& h) { return k25::filteredNdf(params, setup, look.ndf, h); };
            glm::dvec3 cpu = iblref::estimate(iblref::Mode::GlintIs, sp, true, glintNdf, {&params, &setup}, {x, y}, 0u,
                                              0u, constantSky);
            glm::dvec3 gpu(radiance[i], radiance[i + 1], radiance[i + 2]);
            if (cpu != glm::dvec3(0.0)) ++nonZero;
            double error = glm::length(gpu - cpu) / std::max(glm::length(cpu), 0.01);
            if (error <= 0.01) ++agree;
        }
    std::printf("[render vs CPU] %d of %d sphere pixels agree within 1%% (%d non-zero estimates)\n", agree, covered,
                nonZero);
    EXPECT_GT(covered, size * size / 4);
    EXPECT_GT(nonZero, covered / 2);
    EXPECT_GE(agree, int(0.97 * covered));
}
