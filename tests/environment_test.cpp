// Environment lighting through the real GL pipeline (offscreen llvmpipe) against the CPU references of
// engine/render/environment_reference.h: BRDF table, prefiltered mips, SH irradiance, split-sum shading,
// white furnace, sky pixels, the procedural sun, and --env error handling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.h"
#include "core/files.h"
#include "core/image_io.h"
#include "environment/environment.h"
#include "platform/context.h"
#include "reference/environment_reference.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "support/measure.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(Environment, GlContext);

namespace glimmer {
namespace {

namespace fs = std::filesystem;

fs::path outputDir() {
    fs::path dir = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "environment";
    fs::create_directories(dir);
    return dir;
}

fs::path sharedAssets() {
    if (const char* env = std::getenv("GLIMMER_ASSETS_DIR")) return env;
    fs::path beside = fs::path(GLIMMER_SOURCE_DIR) / ".." / "shared" / "assets";
    if (fs::exists(beside)) return beside;
    return "/work/shared/assets";
}

// A smooth synthetic environment with structure at several scales: a sky gradient, a warm side, azimuthal bands
// and two soft lamps (8 and 15 degrees wide, up to 6x the background).
glm::vec3 syntheticRadiance(glm::vec3 d) {
    auto lamp = [&](glm::vec3 axis, float widthDegrees) {
        float angle = std::acos(std::clamp(glm::dot(d, glm::normalize(axis)), -1.0f, 1.0f));
        float x = angle / glm::radians(widthDegrees);
        return std::exp(-x * x);
    };
    float phi = std::atan2(d.x, -d.z), theta = std::acos(std::clamp(d.y, -1.0f, 1.0f));
    glm::vec3 l(0.3f + 0.2f * d.y);
    l += glm::vec3(0.8f, 0.5f, 0.3f) * std::pow(std::max(d.x, 0.0f), 2.0f);
    l += glm::vec3(0.15f) * (1.0f + std::sin(6.0f * phi) * std::sin(4.0f * theta));
    l += glm::vec3(6.0f, 5.0f, 4.0f) * lamp({0.4f, 0.6f, 0.5f}, 8.0f);
    l += glm::vec3(1.0f, 2.0f, 4.0f) * lamp({-0.7f, 0.2f, -0.3f}, 15.0f);
    return l;
}

ImageF syntheticEquirect(int width, int height) {
    ImageF image;
    image.width = width;
    image.height = height;
    image.channels = 3;
    image.pixels.resize(size_t(width) * height * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            glm::vec3 d = envref::equirectToDirection({(x + 0.5f) / width, (y + 0.5f) / height});
            glm::vec3 l = syntheticRadiance(d);
            for (int c = 0; c < 3; ++c) image.pixels[(size_t(y) * width + x) * 3 + c] = l[c];
        }
    return image;
}

// One file per test: ctest runs tests in parallel processes.
fs::path syntheticExr() {
    std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::path path = outputDir() / ("synthetic_env_" + test + ".exr");
    writeImage(path, syntheticEquirect(512, 256));
    return path;
}

envref::CubeImage readCubeLevel(GLuint texture, int level, int faceSize, int layer = 0, int layers = 1) {
    GLint levels = 0;
    glGetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
    EXPECT_LT(level, levels) << "reading a level the texture does not have";
    int size = faceSize >> level;
    std::vector<float> all(size_t(6) * layers * size * size * 4);
    glGetTextureImage(texture, level, GL_RGBA, GL_FLOAT, GLsizei(all.size() * sizeof(float)), all.data());
    envref::CubeImage cube;
    cube.size = size;
    size_t faceFloats = size_t(6) * size * size * 4;
    cube.rgba.assign(all.begin() + faceFloats * layer, all.begin() + faceFloats * (layer + 1));
    return cube;
}

// Rung `rung` (1 .. Environment::kRungs) of the prefiltered ladder for one NDF.
envref::CubeImage readRung(const Environment& env, int rung, int ndf) {
    return readCubeLevel(env.specularFineArray(), Environment::rungMip(rung), Environment::kFaceSize / 2,
                         Environment::rungCube(rung, ndf), 2 * Environment::kSublevels);
}

double relativeError(glm::dvec3 value, glm::dvec3 reference) {
    glm::dvec3 e = glm::abs(value - reference) / glm::max(reference, glm::dvec3(1e-6));
    return std::max({e.x, e.y, e.z});
}

// Headless context, a unit sphere with one editable material, no lights unless added, and a Renderer.
struct SphereRig {
    std::unique_ptr<GLContext> context = createHeadlessContext(Backend::Egl);
    Scene scene;
    std::unique_ptr<GpuScene> gpu;
    std::unique_ptr<Renderer> renderer;
    int size = 128;

    SphereRig() {
        scene.name = "env-test-sphere";
        scene.skyColor = {0.05f, 0.06f, 0.08f};
        scene.meshes.push_back(makeUvSphere(1.0f, 128, 64));
        Material m;
        m.baseColor = glm::vec4(1.0f);
        m.metallic = 0.0f;
        m.alpha = 0.3f;
        m.glinty = false;
        scene.materials.push_back(m);
        scene.instances.push_back({0, 0, glm::mat4(1.0f)});
        Camera camera;
        camera.name = "front";
        camera.position = {0.0f, 0.4f, 3.4f};
        scene.cameras.push_back(camera);
        gpu = std::make_unique<GpuScene>(scene);
        renderer = std::make_unique<Renderer>(defaultShaderDir(), RenderSettings{});
    }
    ~SphereRig() {
        context->makeCurrent();
        renderer.reset();
        gpu.reset();
    }
    Material& material() { return scene.materials[0]; }
    std::vector<float> render(const RenderSettings& settings) {
        gpu->updateMaterialsAndLights(scene);
        renderer->setSettings(settings);
        renderer->renderView(scene, *gpu, scene.cameras[0], size, size);
        return renderer->readHdr();
    }
    glm::dvec3 viewDirection(int x, int y) const {   // unit vector from the surface towards the eye
        return -cameraRay(scene.cameras[0], size, size, x + 0.5, y + 0.5).direction;
    }
};

glm::dvec3 pixel(const std::vector<float>& hdr, int size, int x, int y) {
    const float* p = &hdr[(size_t(y) * size + x) * 4];
    return {p[0], p[1], p[2]};
}
bool isSurface(const std::vector<float>& hdr, int size, int x, int y) {
    return hdr[(size_t(y) * size + x) * 4 + 3] > 0.5f;   // the lighting pass writes alpha 0 on the sky
}

size_t nonFinite(const std::vector<float>& hdr) {
    return size_t(std::count_if(hdr.begin(), hdr.end(), [](float v) { return !std::isfinite(v); }));
}

RenderSettings settingsWith(std::initializer_list<const char*> assignments) {
    RenderSettings s;
    for (const char* a : assignments) s.apply(a);
    return s;
}

}  // namespace

TEST(EnvironmentSpec, ParsesEveryKind) {
    EXPECT_EQ(parseEnvironmentSpec("", "--env").kind, EnvironmentSpec::Kind::Procedural);
    EXPECT_EQ(parseEnvironmentSpec("procedural", "--env").kind, EnvironmentSpec::Kind::Procedural);
    EXPECT_EQ(parseEnvironmentSpec("none", "--env").kind, EnvironmentSpec::Kind::None);
    EnvironmentSpec c = parseEnvironmentSpec("constant:0.5,1,2", "--env");
    EXPECT_EQ(c.kind, EnvironmentSpec::Kind::Constant);
    EXPECT_EQ(c.constant, glm::vec3(0.5f, 1.0f, 2.0f));
    EXPECT_EQ(parseEnvironmentSpec("constant:3", "--env").constant, glm::vec3(3.0f));
    EXPECT_EQ(parseEnvironmentSpec("a/b.hdr", "--env").kind, EnvironmentSpec::Kind::File);
    for (const char* bad : {"constant:", "constant:1,2", "constant:1,x,3", "constant:-1", "constant:nan"})
        EXPECT_THROW(parseEnvironmentSpec(bad, "--env"), UsageError) << bad;
}

// The CPU conventions agree with each other (the GPU passes are checked against them below).
TEST(EnvironmentReference, ConventionsAreConsistent) {
    double total = 0.0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) total += 6.0 * envref::cubeTexelSolidAngle(x, y, 16);
    EXPECT_NEAR(total, 4.0 * M_PI, 1e-9);
    for (glm::vec3 d : {glm::vec3(0.3f, 0.5f, -0.8f), glm::vec3(-0.9f, -0.1f, 0.2f), glm::vec3(0.1f, 0.99f, 0.05f)}) {
        d = glm::normalize(d);
        glm::vec3 back = envref::equirectToDirection(envref::directionToEquirect(d));
        EXPECT_LT(glm::length(back - d), 1e-5f);
    }
    // A white lossless hemisphere: the GGX and Beckmann lobes at f0 = 1 reflect at most everything.
    for (int ndf : {envref::kNdfGgx, envref::kNdfBeckmann}) {
        glm::dvec2 ab = envref::splitSumReference(0.9, 0.2, ndf);
        EXPECT_GT(ab.x + ab.y, 0.9);
        EXPECT_LE(ab.x + ab.y, 1.001);
    }
}

// The split-sum table computed by shaders/environment/brdf_lut.comp (4096 Hammersley samples) against a dense quadrature
// over half vectors. Tolerance 0.01 absolute on A and B (values in [0, 1]): the Hammersley estimate's error at
// 4096 samples is at most about 0.006 (at n.v = 0.07, where the 1 / n.v weight makes it largest; 512 samples
// gave 0.026 there), while a wrong weight, G or Fresnel term is off by far more.
TEST(Environment, BrdfTableMatchesQuadrature) {
    SphereRig rig;
    rig.renderer->prepareEnvironment(rig.scene);   // builds the table with the procedural sky
    const int n = Environment::kBrdfLutSize;
    std::vector<float> lut(size_t(n) * n * 4);
    glGetTextureImage(rig.renderer->environment().brdfLut(), 0, GL_RGBA, GL_FLOAT, GLsizei(lut.size() * sizeof(float)),
                      lut.data());
    double worst = 0.0;
    for (int y : {n / 8, n / 4, n / 2, 3 * n / 4, n - 1})
        for (int x : {n / 16, n / 4, n / 2, 3 * n / 4, n - 1}) {
            double nDotV = (x + 0.5) / n, r = (y + 0.5) / n;
            for (int ndf : {envref::kNdfGgx, envref::kNdfBeckmann}) {
                glm::dvec2 ref = envref::splitSumReference(nDotV, r * r, ndf);
                const float* t = &lut[(size_t(y) * n + x) * 4 + 2 * ndf];
                worst = std::max({worst, std::abs(t[0] - ref.x), std::abs(t[1] - ref.y)});
                EXPECT_NEAR(t[0], ref.x, 0.01) << "A ndf " << ndf << " n.v " << nDotV << " alpha " << r * r;
                EXPECT_NEAR(t[1], ref.y, 0.01) << "B ndf " << ndf << " n.v " << nDotV << " alpha " << r * r;
            }
        }
    std::printf("BRDF table: worst |GPU - quadrature| = %.5f\n", worst);
}

// White furnace: a white Lambertian-base dielectric (metallic 0, base colour 1, not glinty) under a constant
// environment reflects exactly that radiance, at every roughness and NDF, and env.intensity scales it.
TEST(Environment, WhiteFurnaceReturnsTheEnvironmentRadiance) {
    SphereRig rig;
    rig.scene.environment = "constant:0.6,0.8,1.0";
    const glm::dvec3 radiance(0.6, 0.8, 1.0);
    for (NdfType ndf : {NdfType::Ggx, NdfType::Beckmann})
        for (float alpha : {0.05f, 0.3f, 0.8f})
            for (float intensity : {1.0f, 2.0f}) {
                rig.material().alpha = alpha;
                rig.material().ndf = ndf;
                std::string set = "env.intensity=" + std::to_string(intensity);
                RenderSettings settings;
                settings.apply(set);
                std::vector<float> hdr = rig.render(settings);
                ASSERT_EQ(nonFinite(hdr), 0u);
                int surface = 0;
                double worst = 0.0;
                for (int y = 0; y < rig.size; ++y)
                    for (int x = 0; x < rig.size; ++x) {
                        glm::dvec3 expected = radiance * double(intensity);
                        double e = relativeError(pixel(hdr, rig.size, x, y), expected);
                        if (isSurface(hdr, rig.size, x, y)) ++surface;
                        worst = std::max(worst, e);   // sky pixels must show the same radiance
                    }
                EXPECT_GT(surface, rig.size * rig.size / 4);
                EXPECT_LT(worst, 0.01) << "ndf " << int(ndf) << " alpha " << alpha << " intensity " << intensity;
            }
}

// A white metal (f0 = 1) under a constant environment reflects L times the lobe's directional albedo A + B:
// the split sum is exact for a constant environment, so this checks the table lookup in the lighting pass against
// the quadrature at each pixel's n.v. Tolerance 1%: table interpolation between texels and the Hammersley
// estimate (measured worst 0.17%). Pixels with n.v < 0.15 (the last pixel or two of the silhouette) are excluded:
// the G-buffer's interpolated normals differ there from the tessellated geometry's.
TEST(Environment, WhiteMetalReflectsTheLobeAlbedo) {
    SphereRig rig;
    rig.scene.environment = "constant:1,1,1";
    rig.material().metallic = 1.0f;
    RenderSettings normalView;
    normalView.debugView = 2;   // world-space shading normal
    for (NdfType ndf : {NdfType::Ggx, NdfType::Beckmann})
        for (float alpha : {0.1f, 0.5f}) {
            rig.material().alpha = alpha;
            rig.material().ndf = ndf;
            std::vector<float> hdr = rig.render(RenderSettings{});
            std::vector<float> normals = rig.render(normalView);
            int checked = 0;
            double worst = 0.0;
            for (int y = 4; y < rig.size; y += 9)
                for (int x = 4; x < rig.size; x += 9) {
                    if (!isSurface(hdr, rig.size, x, y)) continue;
                    glm::dvec3 n = glm::normalize(pixel(normals, rig.size, x, y));
                    double nDotV = glm::dot(n, rig.viewDirection(x, y));
                    if (nDotV < 0.15) continue;
                    glm::dvec2 ab = envref::splitSumReference(nDotV, alpha, int(ndf));
                    double expected = ab.x + ab.y;
                    worst = std::max(worst, std::abs(pixel(hdr, rig.size, x, y).y - expected) / expected);
                    EXPECT_NEAR(pixel(hdr, rig.size, x, y).y, expected, 0.01 * expected)
                        << "ndf " << int(ndf) << " alpha " << alpha << " n.v " << nDotV;
                    ++checked;
                }
            EXPECT_GT(checked, 50);
            std::printf("white metal ndf %d alpha %.2f: worst relative error vs quadrature albedo %.4f\n", int(ndf),
                        alpha, worst);
        }
}

// The prefiltered rungs (shaders/environment/prefilter.comp, texel quadrature) against the defining integral evaluated by
// quadrature over every texel of the same source cube (read back), on the smooth synthetic map: 4% relative per
// channel at each sampled texel centre and 1.5% on average (the upsampling of the rungs filtered below their face
// size). A wrong lobe (NDF, alpha, rung or layer) is off by more.
TEST(Environment, PrefilteredMipsMatchCpuPrefiltering) {
    SphereRig rig;
    rig.scene.environment = syntheticExr().string();
    rig.renderer->prepareEnvironment(rig.scene);
    const Environment& env = rig.renderer->environment();
    envref::CubeImage source = readCubeLevel(env.sourceCube(), 0, Environment::kFaceSize);
    std::mt19937 rng(7);
    double worst = 0.0, sum = 0.0;
    int count = 0;
    for (int rung = 1; rung <= Environment::kRungs; ++rung)
        for (int ndf : {envref::kNdfGgx, envref::kNdfBeckmann}) {
            envref::CubeImage gpu = readRung(env, rung, ndf);
            for (int i = 0; i < 6; ++i) {
                int face = int(rng() % 6), x = int(rng() % gpu.size), y = int(rng() % gpu.size);
                glm::vec3 r = envref::cubeTexelDirection(face, x, y, gpu.size);
                glm::dvec3 ref = envref::prefilteredRadianceReference(source, r, Environment::rungAlpha(rung), ndf);
                double e = relativeError(glm::dvec3(gpu.texel(face, x, y)), ref);
                worst = std::max(worst, e);
                sum += e;
                ++count;
                EXPECT_LT(e, 0.04) << "rung " << rung << " ndf " << ndf << " face " << face << " texel " << x << ","
                                   << y;
            }
        }
    std::printf("prefiltered mips: relative error vs CPU quadrature: worst %.4f mean %.4f\n", worst, sum / count);
    EXPECT_LT(sum / count, 0.015);
}

// Order-2 SH irradiance against the irradiance integral by quadrature over the source cube. SH9 keeps only the
// low frequencies of the cosine convolution (Ramamoorthi & Hanrahan 2001 bound the error for any lighting at
// about 9%, typically 1-3%); the tolerance is 5% of the mean irradiance, so a wrong basis constant, band weight
// or direction convention (each changes the result by 20% or more here) fails.
TEST(Environment, ShIrradianceMatchesQuadrature) {
    SphereRig rig;
    rig.scene.environment = syntheticExr().string();
    rig.renderer->prepareEnvironment(rig.scene);
    const Environment& env = rig.renderer->environment();
    envref::CubeImage source = readCubeLevel(env.sourceCube(), 2, Environment::kFaceSize);
    const auto& sh = env.irradianceSh();
    std::mt19937 rng(11);
    std::normal_distribution<float> gauss;
    double mean = 0.0;
    std::vector<std::pair<glm::dvec3, glm::dvec3>> pairs;
    for (int i = 0; i < 40; ++i) {
        glm::vec3 n = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)));
        glm::dvec3 ref = envref::diffuseReference(source, n);
        double x = n.x, y = n.y, z = n.z;
        const double basis[9] = {0.282095, 0.488603 * y, 0.488603 * z, 0.488603 * x, 1.092548 * x * y,
                                 1.092548 * y * z,  0.315392 * (3 * z * z - 1), 1.092548 * x * z,
                                 0.546274 * (x * x - y * y)};
        glm::dvec3 value(0.0);
        for (int k = 0; k < 9; ++k) value += glm::dvec3(sh[k]) * basis[k];
        pairs.push_back({value, ref});
        mean += (ref.x + ref.y + ref.z) / 3.0 / 40.0;
    }
    double worst = 0.0;
    for (auto& [value, ref] : pairs) {
        glm::dvec3 e = glm::abs(value - ref);
        worst = std::max({worst, e.x / mean, e.y / mean, e.z / mean});
    }
    std::printf("SH irradiance: worst error / mean = %.4f\n", worst);
    EXPECT_LT(worst, 0.05);
}

// The full lighting pass on a smooth metal sphere (f0 = 1, no lights) under the synthetic map, at sampled pixels.
// (a) Against CPU split sum: CPU-prefiltered radiance at the mirror direction times the quadrature table value,
//     with alpha on a prefiltered rung (rung 8, alpha 0.18) and between rungs (alpha 0.25): 5% per pixel (the
//     prefilter's 4% plus table interpolation and the three-rung interpolation; measured 0.34% on the rung, 0.89%
//     between) and 1.5% on average.
// (b) Against the true reflection integral (Cook-Torrance with Smith G and Schlick F by quadrature over the cube):
//     split-sum is an approximation (it assumes n = v = r for the lobe's shape and ignores its stretching at
//     grazing angles), so the tolerance is looser and stated on the distribution over pixels with n.v >= 0.3:
//     median 4%, 90th percentile 12% (measured: median 1.5-1.7%, p90 7-8%, max 11% for GGX and Beckmann).
//     (b) also runs at alpha = 0.25, between rungs: there the lookup interpolates three rungs' lobes, so there:
//     median 6%, p90 18%.
TEST(Environment, SplitSumShadingMatchesCpu) {
    SphereRig rig;
    rig.scene.environment = syntheticExr().string();
    rig.material().metallic = 1.0f;
    rig.renderer->prepareEnvironment(rig.scene);
    envref::CubeImage source = readCubeLevel(rig.renderer->environment().sourceCube(), 1, Environment::kFaceSize);
    RenderSettings normalView;
    normalView.debugView = 2;
    for (NdfType ndf : {NdfType::Ggx, NdfType::Beckmann})
    for (float alpha : {Environment::rungAlpha(8), 0.25f}) {
        bool onLevel = alpha == Environment::rungAlpha(8);
        rig.material().alpha = alpha;
        rig.material().ndf = ndf;
        std::vector<float> hdr = rig.render(RenderSettings{});
        ASSERT_EQ(nonFinite(hdr), 0u);
        std::vector<float> normals = rig.render(normalView);
        std::vector<double> trueErrors;
        double worstSplit = 0.0, sumSplit = 0.0;
        for (int y = 6; y < rig.size; y += 12)
            for (int x = 6; x < rig.size; x += 12) {
                if (!isSurface(hdr, rig.size, x, y)) continue;
                glm::dvec3 n = glm::normalize(pixel(normals, rig.size, x, y)), v = rig.viewDirection(x, y);
                double nDotV = glm::dot(n, v);
                if (nDotV < 0.3) continue;
                glm::dvec3 r = 2.0 * nDotV * n - v;
                glm::dvec3 value = pixel(hdr, rig.size, x, y);
                glm::dvec2 ab = envref::splitSumReference(nDotV, alpha, int(ndf));
                glm::dvec3 split =
                    envref::prefilteredRadianceReference(source, glm::vec3(r), alpha, int(ndf)) * (ab.x + ab.y);
                double e = relativeError(value, split);   // on a rung and between rungs (the ladder's interpolation)
                worstSplit = std::max(worstSplit, e);
                sumSplit += e;
                EXPECT_LT(e, 0.05) << "split sum, ndf " << int(ndf) << " pixel " << x << "," << y;
                glm::dvec3 truth = envref::specularIntegralReference(source, glm::vec3(n), glm::vec3(v), alpha,
                                                                     int(ndf), glm::vec3(1.0f));
                trueErrors.push_back(relativeError(value, truth));
            }
        ASSERT_GT(trueErrors.size(), 20u);
        EXPECT_LT(sumSplit / trueErrors.size(), 0.015);
        std::sort(trueErrors.begin(), trueErrors.end());
        double median = trueErrors[trueErrors.size() / 2], p90 = trueErrors[trueErrors.size() * 9 / 10];
        std::printf("ndf %d alpha %.2f: split sum vs CPU split sum worst %.4f; vs true integral median %.4f p90 %.4f "
                    "max %.4f\n", int(ndf), alpha, worstSplit, median, p90, trueErrors.back());
        EXPECT_LT(median, onLevel ? 0.04 : 0.06);
        EXPECT_LT(p90, onLevel ? 0.12 : 0.18);
    }
}

// Sky pixels show the map's radiance along the view ray, rotated by env.rotation and scaled by env.intensity.
// Synthetic map: 1% (two bilinear resamplings of a smooth map; measured 0.03%). Real map (skipped without
// ../shared/assets): its detail is resampled twice (equirect -> cube texel centres -> bilinear), so per pixel it
// differs by up to the local contrast; checked on the median (2%) and the 90th percentile (8%) of the relative
// error (measured 0.4% and 2.9%; the maximum, at foliage edges against the sky, is about 190%).
TEST(Environment, SkyPixelsShowTheMap) {
    struct Case { fs::path path; bool smooth; };
    std::vector<Case> cases = {{syntheticExr(), true}};
    fs::path real = sharedAssets() / "hdri" / "immenstadter_horn_1k.hdr";
    if (fs::exists(real)) cases.push_back({real, false});
    else std::printf("skipping the real-map case: %s not found\n", real.string().c_str());
    SphereRig rig;
    rig.scene.cameras[0].position = {0.0f, 0.2f, 3.0f};
    rig.scene.cameras[0].target = {0.6f, 0.9f, 0.0f};   // mostly sky, some sphere
    RenderSettings settings = settingsWith({"env.rotation=30", "env.intensity=1.5"});
    for (const Case& c : cases) {
        rig.scene.environment = c.path.string();
        std::vector<float> hdr = rig.render(settings);
        ASSERT_EQ(nonFinite(hdr), 0u);
        ImageF map = readImage(c.path);
        std::vector<double> errors;
        for (int y = 0; y < rig.size; ++y)
            for (int x = 0; x < rig.size; ++x) {
                if (isSurface(hdr, rig.size, x, y)) continue;
                glm::vec3 d = glm::vec3(-rig.viewDirection(x, y));
                glm::vec3 mapDirection = envref::worldToEnvironment(d, 30.0f);
                glm::dvec3 expected = 1.5 * glm::dvec3(envref::sampleEquirect(map, mapDirection));
                errors.push_back(relativeError(pixel(hdr, rig.size, x, y), expected));
            }
        ASSERT_GT(errors.size(), size_t(rig.size * rig.size / 2));
        std::sort(errors.begin(), errors.end());
        double median = errors[errors.size() / 2], p90 = errors[errors.size() * 9 / 10];
        std::printf("sky %s: median %.4f p90 %.4f max %.4f\n", c.path.filename().c_str(), median, p90, errors.back());
        if (c.smooth) EXPECT_LT(errors.back(), 0.01);
        else {
            EXPECT_LT(median, 0.02);
            EXPECT_LT(p90, 0.08);
        }
    }
}

// --env none restores the constant ambient: sky pixels are Scene::skyColor and a white diffuse surface reflects
// skyColor x ambient. (Ambient occlusion off: it may darken the ambient term, by design; its own tests hold it
// to 1 where nothing occludes.)
TEST(Environment, NoneUsesTheConstantAmbient) {
    SphereRig rig;
    rig.scene.environment = "none";
    std::vector<float> hdr = rig.render(settingsWith({"ambient=2", "ao.enabled=0"}));
    EXPECT_FALSE(rig.renderer->environment().enabled());
    glm::dvec3 sky(rig.scene.skyColor);
    for (int y = 0; y < rig.size; y += 7)
        for (int x = 0; x < rig.size; x += 7) {
            glm::dvec3 expected = isSurface(hdr, rig.size, x, y) ? 2.0 * sky : sky;
            EXPECT_LT(relativeError(pixel(hdr, rig.size, x, y), expected), 1e-4) << x << "," << y;
        }
}

// The procedural sky's sun disk sits on the scene's directional light and delivers its irradiance; since that
// light already shades the scene, the sun stays out of the prefiltered levels and the SH irradiance.
TEST(Environment, ProceduralSunFollowsTheDirectionalLight) {
    SphereRig rig;
    glm::vec3 toward = glm::normalize(glm::vec3(-0.5f, 0.7f, 0.6f));
    rig.scene.lights.push_back({LightType::Directional, toward, glm::vec3(1.0f, 0.9f, 0.8f), 2.0f});
    rig.renderer->prepareEnvironment(rig.scene);
    const Environment& env = rig.renderer->environment();
    envref::CubeImage background = readCubeLevel(env.specularCubeArray(), 0, Environment::kFaceSize, 0, 2);
    // The disk is the only part of the sky above ~10: its radiance-weighted centre and its irradiance.
    glm::dvec3 centre(0.0), irradiance(0.0);
    for (int face = 0; face < 6; ++face)
        for (int y = 0; y < background.size; ++y)
            for (int x = 0; x < background.size; ++x) {
                glm::dvec3 l(background.texel(face, x, y));
                if (l.y < 10.0) continue;
                glm::dvec3 d(envref::cubeTexelDirection(face, x, y, background.size));
                double w = envref::cubeTexelSolidAngle(x, y, background.size);
                centre += d * (l.y * w);
                irradiance += l * w * glm::dot(d, glm::dvec3(toward));
            }
    ASSERT_GT(glm::length(centre), 0.0);
    double angle = std::acos(std::clamp(glm::dot(glm::normalize(centre), glm::dvec3(toward)), -1.0, 1.0));
    EXPECT_LT(glm::degrees(angle), 0.25);
    EXPECT_LT(relativeError(irradiance, glm::dvec3(2.0, 1.8, 1.6)), 0.05);   // sky under the disk adds < 1%
    envref::CubeImage level1 = readRung(env, 1, envref::kNdfGgx);
    float brightest = 0.0f;
    for (size_t i = 0; i < level1.rgba.size(); ++i) brightest = std::max(brightest, level1.rgba[i]);
    EXPECT_GT(brightest, 0.0f);   // the sky is there
    EXPECT_LT(brightest, 5.0f);   // the sun is not
    EXPECT_TRUE(std::all_of(level1.rgba.begin(), level1.rgba.end(), [](float v) { return std::isfinite(v); }));
}

// Bad --env input: one line on stderr naming the flag and the file, non-zero exit, no crash.
TEST(Environment, BadEnvFileGivesOneLineError) {
    fs::path dir = outputDir();
    fs::path missing = dir / "does_not_exist.hdr";
    fs::path garbage = dir / "garbage.hdr";
    { std::ofstream(garbage) << "this is not a radiance file\n"; }
    fs::path truncated = dir / "truncated.exr";
    {
        fs::path good = syntheticExr();
        std::ifstream in(good, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), {});
        std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 3);
    }
    for (const fs::path& bad : {missing, garbage, truncated}) {
        fs::path out = dir / "bad_env.png", err = dir / "bad_env.stderr";
        std::string command = std::string(GLIMMER_EXECUTABLE) + " render --scene sphere --size 32x32 --env '" +
                              bad.string() + "' --out '" + out.string() + "' 2> '" + err.string() + "' > /dev/null";
        int status = std::system(command.c_str());
        EXPECT_NE(status, 0) << bad;
        std::ifstream in(err);
        std::vector<std::string> lines;
        for (std::string line; std::getline(in, line);)
            if (!line.empty()) lines.push_back(line);
        ASSERT_EQ(lines.size(), 1u) << bad;
        EXPECT_NE(lines[0].find("--env"), std::string::npos) << lines[0];
        EXPECT_NE(lines[0].find(bad.string()), std::string::npos) << lines[0];
    }
}

// Every shared HDR map loads, converts and lights the sphere without NaN/Inf (skipped without ../shared/assets).
TEST(Environment, SharedMapsRenderFinite) {
    fs::path dir = sharedAssets() / "hdri";
    if (!fs::is_directory(dir)) GTEST_SKIP() << dir << " not found";
    SphereRig rig;
    rig.size = 64;
    rig.material().metallic = 1.0f;
    rig.material().alpha = 0.1f;
    std::vector<fs::path> all;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".hdr" || entry.path().extension() == ".exr") all.push_back(entry.path());
    std::sort(all.begin(), all.end());
    // CI: the two maps with the most extreme values (studio_small_03's lamps peak at 3568, rooitou_park's sun);
    // GLIMMER_MEASURE=1: every shared map (each costs its environment precompute, about 6 s).
    int maps = 0;
    for (const fs::path& map : test::mapsForThisRun(all)) {
        rig.scene.environment = map.string();
        std::vector<float> hdr = rig.render(RenderSettings{});
        EXPECT_EQ(nonFinite(hdr), 0u) << map;
        EXPECT_TRUE(rig.renderer->environment().enabled());
        double sum = 0.0;
        for (size_t i = 0; i < hdr.size(); i += 4) sum += hdr[i + 1];
        EXPECT_GT(sum, 0.0) << map;
        ++maps;
    }
    EXPECT_GT(maps, 0);
}


// The split sum on every shared map against quadrature (issue 16). Maps with tiny, very bright lamps
// (studio_small_03: up to 3568 against a mean of 1.9) are the hard case.
// (1) Each rung of the prefiltered ladder, at 20 random texels per rung and NDF, against CPU quadrature of the same
//     integral over every texel of the source cube (envref::prefilteredRadianceReference): within 15% at a texel and
//     3% on average (measured 14.3% worst, at rung 2 (alpha 0.05, Beckmann): the narrow rungs are filtered at 64 or
//     32 texels a face and upsampled; filtered importance sampling, which the texel quadrature of
//     shaders/environment/prefilter.comp replaced, was off by up to 2x here).
// (2) The lookup: white metal sphere (96 x 96), both NDFs, the pixels facing the eye (n.v >= 0.8), against the
//     split sum at the material's exact alpha (prefiltered quadrature times the exact (A, B)), at alphas on and
//     between rungs from 0.05 to 1: within 25% (the bound; measured 16.9% worst, studio_small_03, Beckmann,
//     alpha 0.1; with a mip chain's levels 4x apart it was 3.15x). The split sum's own approximation (n = v = r)
//     against the true reflection integral is printed at n.v >= 0.95.
TEST(Environment, SplitSumOnSharedMapsAgainstQuadrature) {
    if (!test::fullMeasurement()) GTEST_SKIP() << "GLIMMER_MEASURE=1 runs it (45 s); CI: SplitSumShadingMatchesCpu, PrefilteredMipsMatchCpuPrefiltering";
    fs::path dir = sharedAssets() / "hdri";
    if (!fs::is_directory(dir)) GTEST_SKIP() << dir << " not found";
    SphereRig rig;
    rig.size = 96;
    rig.material().metallic = 1.0f;
    RenderSettings normalView;
    normalView.debugView = 2;
    std::vector<fs::path> maps;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().extension() == ".hdr" || entry.path().extension() == ".exr") maps.push_back(entry.path());
    std::sort(maps.begin(), maps.end());
    ASSERT_FALSE(maps.empty());
    // CI keeps the two maps that bound the errors (studio_small_03: the worst lookup, a small bright lamp;
    // rooitou_park: a wide sky); GLIMMER_MEASURE=1 runs all five (about 110 s on 2 cores).
    maps = test::mapsForThisRun(maps);
    auto mean = [](glm::dvec3 c) { return (c.x + c.y + c.z) / 3.0; };
    double worstRung = 0.0, worstLookup = 0.0;
    for (const fs::path& map : maps) {
        rig.scene.environment = map.string();
        rig.renderer->prepareEnvironment(rig.scene);
        const Environment& env = rig.renderer->environment();
        // Level 1 of the source (128^2 faces) for every reference: level 0 gave the same errors within 0.3% and four
        // times the test's time.
        envref::CubeImage source = readCubeLevel(env.sourceCube(), 1, Environment::kFaceSize);
        std::mt19937 rng(7);
        for (int rung = 1; rung <= Environment::kRungs; ++rung)
            for (int ndf : {envref::kNdfGgx, envref::kNdfBeckmann}) {
                envref::CubeImage gpu = readRung(env, rung, ndf);
                double worst = 0.0, sum = 0.0;
                for (int i = 0; i < 20; ++i) {
                    int face = int(rng() % 6), x = int(rng() % gpu.size), y = int(rng() % gpu.size);
                    glm::vec3 r = envref::cubeTexelDirection(face, x, y, gpu.size);
                    glm::dvec3 ref = envref::prefilteredRadianceReference(source, r, Environment::rungAlpha(rung), ndf);
                    double e = relativeError(glm::dvec3(gpu.texel(face, x, y)), ref);
                    worst = std::max(worst, e);
                    sum += e;
                }
                std::printf("[ rungs     ] %-26s rung %2d (alpha %.3f) ndf %d: worst %.3f mean %.3f\n",
                            map.filename().string().c_str(), rung, Environment::rungAlpha(rung), ndf, worst, sum / 20.0);
                EXPECT_LT(worst, 0.15) << map.filename() << " rung " << rung << " ndf " << ndf;
                EXPECT_LT(sum / 20.0, 0.03) << map.filename() << " rung " << rung << " ndf " << ndf;
                worstRung = std::max(worstRung, worst);
            }
        std::vector<float> normals = rig.render(normalView);
        for (NdfType ndf : {NdfType::Ggx, NdfType::Beckmann})
            for (float alpha : {0.05f, 0.1f, 0.16f, 0.25f, 0.36f, 0.5f, 0.8f, 1.0f}) {
                rig.material().alpha = alpha;
                rig.material().ndf = ndf;
                std::vector<float> hdr = rig.render(RenderSettings{});
                double worst = 0.0, sum = 0.0, worstTruth = 0.0;
                int count = 0;
                for (int y = 4; y < rig.size; y += 8)
                    for (int x = 4; x < rig.size; x += 8) {
                        if (!isSurface(hdr, rig.size, x, y)) continue;
                        glm::dvec3 n = glm::normalize(pixel(normals, rig.size, x, y)), v = rig.viewDirection(x, y);
                        double nDotV = glm::dot(n, v);
                        if (nDotV < 0.8) continue;
                        glm::dvec3 r = 2.0 * nDotV * n - v;
                        glm::dvec2 ab = envref::splitSumReference(nDotV, alpha, int(ndf));
                        double split =
                            mean(envref::prefilteredRadianceReference(source, glm::vec3(r), alpha, int(ndf))) *
                            (ab.x + ab.y);
                        // Relative error of the channel mean (a lamp's colour ratios are not the point).
                        double value = mean(pixel(hdr, rig.size, x, y));
                        double e = std::abs(value - split) / std::max(split, 1e-6);
                        worst = std::max(worst, e);
                        sum += e;
                        ++count;
                        if (nDotV >= 0.95) {
                            double truth = mean(envref::specularIntegralReference(
                                source, glm::vec3(n), glm::vec3(v), alpha, int(ndf), glm::vec3(1.0f)));
                            worstTruth = std::max(worstTruth, std::abs(value - truth) / std::max(truth, 1e-6));
                        }
                    }
                ASSERT_GT(count, 12);
                std::printf("[ split sum ] %-26s ndf %d alpha %.2f: against quadrature worst %.3f mean %.3f (%d px); "
                            "against the true integral at n.v >= 0.95 worst %.3f\n",
                            map.filename().string().c_str(), int(ndf), alpha, worst, sum / count, count, worstTruth);
                EXPECT_LT(worst, 0.25) << map.filename() << " ndf " << int(ndf) << " alpha " << alpha;
                worstLookup = std::max(worstLookup, worst);
            }
    }
    std::printf("[ split sum ] worst over every map: rungs %.3f, lookup %.3f\n", worstRung, worstLookup);
}
}  // namespace glimmer
