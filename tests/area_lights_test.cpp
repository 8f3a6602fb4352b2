// Area lights through the GL pipeline (shaders/lights/, the lighting pass), on a plane seen from above at 96x96:
// - the rendered radiance of rect and sphere lights (a sphere runs the disks' ellipse-cone code) equals the CPU
//   reference of the same LTC formulas (engine/reference/area_light_reference.h) pixel by pixel, for GGX and
//   Beckmann; its distance to brute-force quadrature of the BRDF over the light is printed (the LTC's own error);
// - glints under an area light (deliot2023, Kneiphof & Klein 2024): the mean over the plane equals the smooth LTC
//   render's within 5 % for both the specular and the NDF-only LTC and for Eq. 4's probability, they converge to it
//   at high density, and a method without its own area-light glints (zirr2016) keeps the mean too;
// - soft shadows: a box under a sphere light casts a penumbra that widens with the light's radius.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/files.h"
#include "ltc_fitter.h"
#include "platform/context.h"
#include "reference/area_light_reference.h"
#include "render/aov.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/mesh_builder.h"
#include "support/test_needs.h"

// What this suite needs beyond the CPU (its ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(AreaLights, GlContext);

namespace glimmer {
namespace {

namespace lf = ltcfit;
using reference::AreaLightGeometry;
using reference::AreaShape;

constexpr double kPi = 3.14159265358979323846;

// A plane on y = 0 seen from above and a little to the side, one light, no environment and no ambient.
struct AreaRig {
    std::unique_ptr<GLContext> context = createHeadlessContext(Backend::Egl);
    Scene scene;
    Camera camera;
    std::unique_ptr<GpuScene> gpu;
    std::unique_ptr<Renderer> renderer;
    int size = 128;

    AreaRig(const Light& light, float alpha, NdfType ndf, bool glinty = false, bool withBox = false) {
        scene.name = "area-light-test";
        scene.environment = "none";
        scene.skyColor = glm::vec3(0.0f);
        scene.meshes.push_back(makeGroundPlane(4.0f, 8, 0.0f));
        Material ground;
        ground.baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
        ground.alpha = alpha;
        ground.ndf = ndf;
        ground.metallic = 0.0f;
        ground.glinty = glinty;
        scene.materials = {ground};
        scene.instances = {{0, 0, glm::mat4(1.0f)}};
        if (withBox) {
            MeshBuilder b("box");
            b.box({-0.3f, 0.6f, -0.3f}, {0.3f, 0.8f, 0.3f}, {0.0f, 0.0f, 0.0f});
            scene.meshes.push_back(b.finish());
            Material box = ground;
            box.doubleSided = false;
            box.glinty = false;
            scene.materials.push_back(box);
            scene.instances.push_back({1, 1, glm::mat4(1.0f)});
        }
        scene.lights = {light};
        camera.name = "above";
        camera.position = {0.0f, 4.0f, 3.0f};
        camera.target = {0.0f, 0.0f, -0.2f};
        camera.verticalFovDegrees = 45.0f;
        scene.cameras = {camera};
        gpu = std::make_unique<GpuScene>(scene);
        renderer = std::make_unique<Renderer>(defaultShaderDir(), RenderSettings{});
    }
    ~AreaRig() {
        context->makeCurrent();
        renderer.reset();
        gpu.reset();
    }
    std::vector<float> render(RenderSettings settings) {
        settings.common["ambient"] = 0.0f;
        settings.common["ao.enabled"] = 0.0f;
        gpu->updateMaterialsAndLights(scene);
        renderer->setSettings(settings);
        renderer->renderView(scene, *gpu, camera, size, size);
        return renderer->readHdr();
    }
    // The plane point seen through pixel (x, y) (bottom-up rows, as readHdr), or false.
    bool planePoint(int x, int y, glm::dvec3& p) const {
        Ray ray = cameraRay(camera, size, size, x + 0.5, y + 0.5);
        if (ray.direction.y >= 0.0) return false;
        p = ray.origin - ray.direction * (ray.origin.y / ray.direction.y);
        return std::abs(p.x) < 3.9 && std::abs(p.z) < 3.9;
    }
};

AreaLightGeometry geometryOf(const Light& light) {
    GpuLight g = gpuLight(light);
    AreaLightGeometry geometry;
    geometry.shape = light.type == LightType::Rect ? AreaShape::Rect : light.type == LightType::Disk ? AreaShape::Disk
                                                                                                   : AreaShape::Sphere;
    geometry.centre = glm::dvec3(light.vector);
    geometry.halfU = glm::dvec3(glm::vec3(g.areaU));
    geometry.halfV = glm::dvec3(glm::vec3(g.areaV));
    geometry.radius = light.radius;
    geometry.twoSided = light.twoSided;
    return geometry;
}

Light rectLight() {
    Light l;
    l.type = LightType::Rect;
    l.vector = {0.3f, 1.2f, -0.8f};
    l.spotDirection = glm::normalize(glm::vec3(0.0f, -1.0f, 0.35f));
    l.right = {1.0f, 0.0f, 0.0f};
    l.width = 1.2f;
    l.height = 0.5f;
    l.intensity = 3.0f;
    l.color = {1.0f, 0.9f, 0.8f};
    return l;
}
// A one-sided rect standing on the plane, facing +z, its lower edge 5 cm below the plane, with a range of 2.5 m:
// the plane behind it, beyond its range and under its lower strip gets nothing of it (the lighting pass skips the
// light there: lights/area_light.glsl areaLightReaches), the rest the part above the horizon.
Light standingRectLight() {
    Light l;
    l.type = LightType::Rect;
    l.vector = {0.2f, 0.3f, -0.5f};
    l.spotDirection = {0.0f, 0.0f, 1.0f};
    l.right = {1.0f, 0.0f, 0.0f};
    l.width = 1.2f;
    l.height = 0.7f;
    l.range = 2.5f;
    l.intensity = 3.0f;
    l.color = {1.0f, 0.9f, 0.8f};
    return l;
}
Light sphereLight() {
    Light l;
    l.type = LightType::Sphere;
    l.vector = {-0.4f, 0.7f, -0.5f};
    l.radius = 0.25f;
    l.intensity = 2.0f;
    return l;
}

RenderSettings smoothSettings() {
    RenderSettings s;
    s.method = "smooth";
    s.common["shadow.enabled"] = 0.0f;
    return s;
}

// The lighting pass's radiance of a dielectric plane (base colour 0.5, f0 0.04) under `light`, from the CPU
// reference of the same formulas (LTC integrals, the tables' A, B).
double referenceRadiance(const Light& light, const glm::dvec3& p, const glm::dvec3& eye, double alpha, bool beckmann,
                         int channel) {
    const glm::dvec3 n(0.0, 1.0, 0.0), toEye = glm::normalize(eye - p);
    AreaLightGeometry g = geometryOf(light);
    glm::dmat3 frame = reference::ltcFrame(n, toEye);
    reference::LtcLookup look = reference::ltcLookup(alpha, glm::dot(n, toEye), beckmann);
    double diffuse = reference::ltcIntegral(g, p, frame, glm::dmat3(1.0));
    double specular = (0.04 * look.A + look.B) * reference::ltcIntegral(g, p, frame, look.invSpecular);
    const double window = rangeWindow(float(glm::distance(p, glm::dvec3(light.vector))), light.range);
    return double(light.color[channel]) * light.radianceScale() * window * (0.5 * diffuse + specular);
}

TEST(AreaLights, RenderMatchesTheCpuLtcReference) {
    struct Case {
        const char* name;
        Light light;
        NdfType ndf;
    };
    // The disk's shader path is the sphere's (an ellipse's cone); the CPU tests cover the disk against brute force.
    const Case cases[] = {{"rect GGX", rectLight(), NdfType::Ggx},
                          {"rect Beckmann", rectLight(), NdfType::Beckmann},
                          {"standing rect GGX", standingRectLight(), NdfType::Ggx},
                          {"sphere GGX", sphereLight(), NdfType::Ggx}};
    for (const Case& c : cases) {
        const float alpha = 0.25f;
        AreaRig rig(c.light, alpha, c.ndf);
        rig.size = 96;
        std::vector<float> hdr = rig.render(smoothSettings());
        int compared = 0, bad = 0;
        double worst = 0.0, sumTruth = 0.0, sumError = 0.0;
        for (int y = 0; y < rig.size; ++y)
            for (int x = 0; x < rig.size; ++x) {
                glm::dvec3 p;
                if (!rig.planePoint(x, y, p)) continue;
                double expected = referenceRadiance(c.light, p, glm::dvec3(rig.camera.position), alpha,
                                                    c.ndf == NdfType::Beckmann, 0);
                double got = hdr[(size_t(y) * rig.size + size_t(x)) * 4];
                double error = std::abs(got - expected) / (expected + 0.02);
                worst = std::max(worst, error);
                bad += error > 0.03 ? 1 : 0;
                ++compared;
                // Every 29th pixel against brute-force quadrature of the BRDF over the light (the LTC's own error).
                if ((x * 7 + y) % 29 == 0) {
                    const glm::dvec3 n(0.0, 1.0, 0.0), v = glm::normalize(glm::dvec3(rig.camera.position) - p);
                    double truth = reference::integrateOverLight(geometryOf(c.light), p, [&](const glm::dvec3& l) {
                        double nl = glm::dot(n, l);
                        if (nl <= 0.0) return 0.0;
                        glm::dmat3 frame = reference::ltcFrame(n, v);
                        glm::dvec3 vs = frame * v, ls = frame * l, h = glm::normalize(vs + ls);
                        double F = 0.04 + 0.96 * std::pow(1.0 - glm::dot(vs, h), 5.0);
                        return 0.5 / kPi * nl + F * lf::lobeValue(c.ndf == NdfType::Beckmann ? lf::Ndf::Beckmann : lf::Ndf::Ggx,
                                                                  lf::Lobe::Specular, alpha, vs, ls);
                    }, 48) * double(c.light.color[0]) * c.light.radianceScale() *
                        rangeWindow(float(glm::distance(p, glm::dvec3(c.light.vector))), c.light.range);
                    sumTruth += truth;
                    sumError += std::abs(got - truth);
                }
            }
        std::printf("%-14s %d pixels: worst |GPU - CPU LTC| / (CPU + 0.02) %.4f; vs brute force: mean |error| %.1f%% of "
                    "the mean radiance\n", c.name, compared, worst, 100.0 * sumError / std::max(sumTruth, 1e-12));
        EXPECT_GT(compared, 3000) << c.name;
        EXPECT_LE(bad, compared / 200) << c.name << ": pixels more than 3% off the CPU reference";
        EXPECT_LT(worst, 0.08) << c.name;
    }
}

// The plane's pixels: the sum of the red channel and its 99.9th percentile.
struct PlaneStats {
    double sum = 0.0, p999 = 0.0, mean = 0.0;
};
PlaneStats planeStats(const AreaRig& rig, const std::vector<float>& hdr) {
    PlaneStats stats;
    std::vector<float> values;
    for (int y = 0; y < rig.size; ++y)
        for (int x = 0; x < rig.size; ++x) {
            glm::dvec3 p;
            if (!rig.planePoint(x, y, p)) continue;
            values.push_back(hdr[(size_t(y) * rig.size + size_t(x)) * 4]);
            stats.sum += values.back();
        }
    std::sort(values.begin(), values.end());
    stats.mean = stats.sum / double(std::max<size_t>(values.size(), 1));
    stats.p999 = values.empty() ? 0.0 : values[size_t(0.999 * double(values.size() - 1))];
    return stats;
}

// Kneiphof & Klein 2024: the glint factor's expectation is 1, so over many footprints the glinty plane's radiance
// averages to the smooth LTC render's (sparse glints: e^9 facets per unit UV area, a few reflecting per pixel at
// most); at high density every pixel converges to it.
TEST(AreaLights, GlintsUnderAnAreaLightAverageToTheSmoothLtc) {
    const float alpha = 0.3f;
    AreaRig rig(rectLight(), alpha, NdfType::Ggx, true);
    rig.size = 96;
    const PlaneStats smooth = planeStats(rig, rig.render(smoothSettings()));
    struct Case {
        const char* name;
        const char* method;
        std::vector<std::string> sets;
    };
    const Case cases[] = {
        {"deliot2023 kk24, specular LTC", "deliot2023", {}},
        {"deliot2023 kk24, NDF-only LTC", "deliot2023", {"deliot2023.light_integral=ndf_ltc"}},
        {"deliot2023 db23", "deliot2023", {"deliot2023.probability=db23"}},
        {"zirr2016 (a point at the centre)", "zirr2016", {}},
    };
    for (const Case& c : cases) {
        RenderSettings s = smoothSettings();
        s.method = c.method;
        s.apply(std::string(c.method) + ".log_density=9");
        for (const std::string& set : c.sets) s.apply(set);
        PlaneStats glints = planeStats(rig, rig.render(s));
        std::printf("%-40s mean / smooth LTC = %.4f, p99.9 / mean = %.1f\n", c.name, glints.sum / smooth.sum,
                    glints.p999 / glints.mean);
        EXPECT_NEAR(glints.sum / smooth.sum, 1.0, 0.05) << c.name;
        EXPECT_GT(glints.p999 / glints.mean, 2.0) << c.name << ": no glints";
    }
    // Convergence: at e^40 facets per unit UV area every pixel is the smooth LTC value.
    RenderSettings dense = smoothSettings();
    dense.method = "deliot2023";
    dense.apply("deliot2023.log_density=40");
    std::vector<float> a = rig.render(smoothSettings()), b = rig.render(dense);
    double worst = 0.0;
    for (size_t i = 0; i < a.size(); i += 4) worst = std::max(worst, std::abs(double(a[i]) - b[i]) / (a[i] + 0.01));
    std::printf("deliot2023 at log density 40: worst |glinty - smooth| / (smooth + 0.01) = %.4f\n", worst);
    EXPECT_LT(worst, 0.02);
}

// Soft shadows: a box under a sphere light; the penumbra (pixels with visibility strictly between 0.05 and 0.95)
// grows with the light's radius, and a light of radius 0 casts the hard PCF shadow.
TEST(AreaLights, SoftShadowPenumbraGrowsWithTheLightSize) {
    int previous = -1;
    for (float radius : {0.0f, 0.15f, 0.4f}) {
        Light light;
        light.type = radius > 0.0f ? LightType::Sphere : LightType::Point;
        light.vector = {0.0f, 1.8f, 0.0f};
        light.radius = radius;
        light.intensity = 3.0f;
        AreaRig rig(light, 0.4f, NdfType::Ggx, false, true);
        RenderSettings s = smoothSettings();
        s.common["shadow.enabled"] = 1.0f;
        s.debugView = findAov("shadow").viewId;
        std::vector<float> visibility = rig.render(s);
        int penumbra = 0, umbra = 0;
        for (int y = 0; y < rig.size; ++y)
            for (int x = 0; x < rig.size; ++x) {
                glm::dvec3 p;
                if (!rig.planePoint(x, y, p) || (std::abs(p.x) < 0.32 && std::abs(p.z) < 0.32)) continue;
                float v = visibility[(size_t(y) * rig.size + size_t(x)) * 4];
                penumbra += v > 0.05f && v < 0.95f ? 1 : 0;
                umbra += v <= 0.05f ? 1 : 0;
            }
        std::printf("light radius %.2f m: %d penumbra pixels, %d umbra pixels\n", radius, penumbra, umbra);
        EXPECT_GT(penumbra, previous) << "radius " << radius;
        if (radius == 0.0f) EXPECT_GT(umbra, 200);
        previous = penumbra;
    }
}

}  // namespace
}  // namespace glimmer
