// Shadows through the real GL pipeline (render/shadows/shadow_maps.h, shaders/shadows/shadows.glsl), judged by a CPU ray
// cast: an occluder box over a ground plane, seen from above at 256x256.
// - the sun's shadow boundary (--aov shadow < 0.5) lies where the analytic projection of the box puts it, within
//   2 px, at 45 degrees and at a grazing 12 degrees with the box resting on the plane (no acne on the lit plane,
//   no peter-panning at the contact);
// - outside the shadow the image is bit-identical to a render with shadows off;
// - a glinty plane has no glint radiance inside the shadow, for every glint method;
// - a camera translation smaller than a shadow texel does not move the shadow edge by more than 0.5 px;
// - cached maps: a still camera renders no shadow view after the first frame;
// - a point light's cube shadow, across two cube faces, within 2 px of the analytic central projection;
// - a spot light's shadow (one view for a narrow cone, a cube for a wide one) within 2 px of the same projection,
//   cached, with the lit side unchanged and no glint radiance in its shadow.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "core/files.h"
#include "platform/context.h"
#include "render/aov.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "render/shadows/shadow_maps.h"
#include "scene/builtin_scenes.h"
#include "scene/mesh_builder.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(Shadows, GlContext);

namespace glimmer {
namespace {

struct Box {
    glm::dvec3 lo, hi;
};

// Slab test: the ray's entry distance into the box, or a negative value when it misses.
double rayBox(const glm::dvec3& origin, const glm::dvec3& direction, const Box& box) {
    double t0 = 0.0, t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(direction[a]) < 1e-12) {
            if (origin[a] < box.lo[a] || origin[a] > box.hi[a]) return -1.0;
            continue;
        }
        double ta = (box.lo[a] - origin[a]) / direction[a], tb = (box.hi[a] - origin[a]) / direction[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    return t0 <= t1 ? t0 : -1.0;
}

enum Pixel : int { kExcluded = -1, kLit = 0, kShadowed = 1 };

// A plane on y = 0 (material 0) and a box (material 1), one light, a camera looking down, no environment.
struct ShadowRig {
    std::unique_ptr<GLContext> context = createHeadlessContext(Backend::Egl);
    Scene scene;
    Box box;
    std::unique_ptr<GpuScene> gpu;
    std::unique_ptr<Renderer> renderer;
    int size = 256;
    int analyticLight = 0;   // the light analytic() classifies for

    ShadowRig(const Box& occluder, const Light& light, float planeHalfExtent = 6.0f) : box(occluder) {
        scene.name = "shadow-test";
        scene.environment = "none";
        scene.skyColor = glm::vec3(0.1f);
        scene.meshes.push_back(makeGroundPlane(planeHalfExtent, 4, 0.0f));
        MeshBuilder b("box");
        b.box(glm::vec3(box.lo), glm::vec3(box.hi), glm::vec3(box.lo));
        scene.meshes.push_back(b.finish());
        Material ground;
        ground.baseColor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
        ground.alpha = 0.4f;
        Material occluderMaterial = ground;
        occluderMaterial.doubleSided = false;   // a closed solid
        scene.materials = {ground, occluderMaterial};
        scene.instances = {{0, 0, glm::mat4(1.0f)}, {1, 1, glm::mat4(1.0f)}};
        scene.lights = {light};
        Camera camera;
        camera.name = "top";
        camera.position = {0.0f, 10.0f, 0.0f};
        camera.target = {0.0f, 0.0f, 0.0f};
        camera.up = {0.0f, 0.0f, -1.0f};
        camera.verticalFovDegrees = 40.0f;
        scene.cameras = {camera};
        gpu = std::make_unique<GpuScene>(scene);
        renderer = std::make_unique<Renderer>(defaultShaderDir(), RenderSettings{});
    }
    ~ShadowRig() {
        context->makeCurrent();
        renderer.reset();
        gpu.reset();
    }
    std::vector<float> render(const RenderSettings& settings, const Camera& camera) {
        gpu->updateMaterialsAndLights(scene);
        renderer->setSettings(settings);
        renderer->renderView(scene, *gpu, camera, size, size);
        return renderer->readHdr();
    }
    std::vector<float> visibility(RenderSettings settings, const Camera& camera) {
        settings.debugView = findAov("shadow").viewId;
        return render(settings, camera);
    }

    // The analytic classification: the camera ray's hit on the plane is shadowed when the ray from it towards
    // the light meets the box; pixels that see the box (or miss the plane) are excluded.
    std::vector<int> analytic(const Camera& camera) const {
        std::vector<int> classes(size_t(size) * size, kExcluded);
        const Light& light = scene.lights[size_t(analyticLight)];
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                Ray ray = cameraRay(camera, size, size, x + 0.5, y + 0.5);
                if (ray.direction.y >= 0.0) continue;
                double tPlane = -ray.origin.y / ray.direction.y;
                double tBox = rayBox(ray.origin, ray.direction, box);
                if (tBox >= 0.0 && tBox < tPlane) continue;
                glm::dvec3 p = ray.origin + tPlane * ray.direction;
                if (light.type == LightType::Spot) {
                    // Outside the cone (less a margin for the falloff's last percent) no light arrives to shadow.
                    double cosAxis = glm::dot(glm::normalize(p - glm::dvec3(light.vector)), glm::dvec3(light.spotDirection));
                    if (cosAxis < std::cos(double(light.outerConeAngle) - 0.03)) continue;
                }
                glm::dvec3 towardLight = light.type == LightType::Directional
                                             ? glm::normalize(glm::dvec3(light.vector))
                                             : glm::dvec3(light.vector) - p;
                double hit = rayBox(p, towardLight, box);
                bool shadowed = hit > 0.0 && (light.type == LightType::Directional || hit < 1.0);
                classes[size_t(y) * size + size_t(x)] = shadowed ? kShadowed : kLit;
            }
        return classes;
    }
    static float red(const std::vector<float>& hdr, int size, int x, int y) { return hdr[(size_t(y) * size + size_t(x)) * 4]; }
};

// True when a pixel of another class (the analytic boundary, or the box's silhouette) lies within `radius` px.
bool nearBoundary(const std::vector<int>& classes, int size, int x, int y, int radius) {
    int own = classes[size_t(y) * size + size_t(x)];
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            if (dx * dx + dy * dy > radius * radius) continue;
            int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= size || yy >= size) continue;
            if (classes[size_t(yy) * size + size_t(xx)] != own) return true;
        }
    return false;
}

struct BoundaryCheck {
    int shadowedPixels = 0, litPixels = 0, misplaced = 0, firstX = -1, firstY = -1;
};

// Writes the visibility and the analytic classes as one greyscale PGM side by side (top row first) under
// <build>/test-output/shadows/ when a check fails, so the misplaced pixels can be looked at.
void writeDiagnostic(const std::vector<int>& classes, const std::vector<float>& visibility, int size) {
    std::filesystem::path dir = std::filesystem::path(GLIMMER_TEST_OUTPUT_DIR) / "shadows";
    std::filesystem::create_directories(dir);
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::ofstream out(dir / (name + ".pgm"), std::ios::binary);
    out << "P5 " << 2 * size << " " << size << " 255\n";
    for (int y = size - 1; y >= 0; --y) {
        for (int x = 0; x < size; ++x)
            out.put(char(std::clamp(ShadowRig::red(visibility, size, x, y), 0.0f, 1.0f) * 255.0f));
        for (int x = 0; x < size; ++x) {
            int c = classes[size_t(y) * size + size_t(x)];
            out.put(char(c == kExcluded ? 128 : c == kLit ? 255 : 0));
        }
    }
}

BoundaryCheck checkBoundary(const std::vector<int>& classes, const std::vector<float>& visibility, int size,
                            bool diagnose = true) {
    BoundaryCheck check;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            int c = classes[size_t(y) * size + size_t(x)];
            if (c == kExcluded) continue;
            (c == kShadowed ? check.shadowedPixels : check.litPixels) += 1;
            bool gpuShadowed = ShadowRig::red(visibility, size, x, y) < 0.5f;
            if (gpuShadowed == (c == kShadowed) || nearBoundary(classes, size, x, y, 2)) continue;
            if (check.misplaced++ == 0) check.firstX = x, check.firstY = y;
        }
    if (check.misplaced > 0 && diagnose) writeDiagnostic(classes, visibility, size);
    return check;
}

Light sunAt(float elevationDegrees, float azimuthDegrees) {
    Light light;
    light.type = LightType::Directional;
    float e = glm::radians(elevationDegrees), a = glm::radians(azimuthDegrees);
    light.vector = {std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)};
    light.intensity = 2.0f;
    return light;
}

TEST(Shadows, SunShadowBoundaryMatchesTheAnalyticProjection) {
    ShadowRig rig({{-0.5, 1.0, -0.6}, {0.5, 1.6, 0.6}}, sunAt(45.0f, 30.0f));
    const Camera& camera = rig.scene.cameras[0];
    std::vector<int> classes = rig.analytic(camera);
    BoundaryCheck check = checkBoundary(classes, rig.visibility(RenderSettings{}, camera), rig.size);
    EXPECT_GT(check.shadowedPixels, 2000) << "the analytic shadow should cover a few thousand pixels";
    EXPECT_EQ(check.misplaced, 0) << "first misplaced pixel at (" << check.firstX << ", " << check.firstY << ")";
}

TEST(Shadows, GrazingSunOnARestingBoxHasNoAcneAndNoPeterPanning) {
    // Sun 12 degrees above the horizon; the box stands on the plane, so the shadow starts at its base.
    ShadowRig rig({{-0.4, 0.0, -0.4}, {0.4, 0.5, 0.4}}, sunAt(12.0f, 200.0f));
    const Camera& camera = rig.scene.cameras[0];
    std::vector<int> classes = rig.analytic(camera);
    std::vector<float> visibility = rig.visibility(RenderSettings{}, camera);
    BoundaryCheck check = checkBoundary(classes, visibility, rig.size);
    EXPECT_GT(check.shadowedPixels, 2000);
    EXPECT_EQ(check.misplaced, 0) << "first misplaced pixel at (" << check.firstX << ", " << check.firstY << ")";
    // No acne: every lit plane pixel away from the boundary sees the whole light.
    int partial = 0;
    for (int y = 0; y < rig.size; ++y)
        for (int x = 0; x < rig.size; ++x)
            if (classes[size_t(y) * rig.size + size_t(x)] == kLit && !nearBoundary(classes, rig.size, x, y, 3))
                partial += ShadowRig::red(visibility, rig.size, x, y) != 1.0f;
    EXPECT_EQ(partial, 0) << "lit plane pixels with visibility below 1 (acne)";

    // The checks can fail: without any bias the lit plane shows acne, with every bias at its maximum the shadow
    // detaches from the box's base (peter-panning).
    RenderSettings unbiased;
    for (const char* s : {"shadow.bias=0", "shadow.normal_bias=0", "shadow.slope_bias=0"}) unbiased.apply(s);
    std::vector<float> acne = rig.visibility(unbiased, camera);
    int acnePixels = 0;
    for (int y = 0; y < rig.size; ++y)
        for (int x = 0; x < rig.size; ++x)
            if (classes[size_t(y) * rig.size + size_t(x)] == kLit && !nearBoundary(classes, rig.size, x, y, 3))
                acnePixels += ShadowRig::red(acne, rig.size, x, y) < 0.5f;
    EXPECT_GT(acnePixels, 100) << "no acne without bias: the acne check above proves nothing";
    RenderSettings overbiased;
    for (const char* s : {"shadow.bias=8", "shadow.normal_bias=8", "shadow.slope_bias=16"}) overbiased.apply(s);
    EXPECT_GT(checkBoundary(classes, rig.visibility(overbiased, camera), rig.size, false).misplaced, 0)
        << "maximal bias still placed the boundary within 2 px: the peter-panning check proves nothing";
}

// Renders with and without shadows (ambient occlusion off in both: it darkens the ambient under the box too, and
// the tests isolate the shadow) and compares them away from the analytic boundary: lit pixels must be unchanged,
// shadowed ones hold only the constant ambient (sky 0.1 x albedo 0.7) and be darker than unshadowed, by at least
// `darkerRatio` (0: any amount; near a spot's cone edge the light adds little).
struct ShadowedComparison {
    int litCompared = 0, litChanged = 0, shadowCompared = 0, notAmbient = 0;
};
ShadowedComparison compareWithShadowsOff(ShadowRig& rig, const Camera& camera, const std::vector<int>& classes,
                                         float darkerRatio) {
    RenderSettings on;
    on.apply("ao.enabled=0");
    RenderSettings off = on;
    off.apply("shadow.enabled=0");
    std::vector<float> with = rig.render(on, camera), without = rig.render(off, camera);
    ShadowedComparison result;
    for (int y = 0; y < rig.size; ++y)
        for (int x = 0; x < rig.size; ++x) {
            int c = classes[size_t(y) * rig.size + size_t(x)];
            if (c == kExcluded || nearBoundary(classes, rig.size, x, y, 3)) continue;
            size_t i = (size_t(y) * rig.size + size_t(x)) * 4;
            if (c == kLit) {
                ++result.litCompared;
                for (int k = 0; k < 3; ++k) result.litChanged += with[i + k] != without[i + k];
            } else {
                ++result.shadowCompared;
                bool darker = darkerRatio > 0.0f ? with[i] < darkerRatio * without[i] : with[i] < without[i];
                result.notAmbient += !darker || std::abs(with[i] - 0.07f) > 1e-3f;
            }
        }
    return result;
}

TEST(Shadows, LitSideIsUnchangedAndTheShadowHoldsOnlyAmbient) {
    ShadowRig rig({{-0.5, 1.0, -0.6}, {0.5, 1.6, 0.6}}, sunAt(45.0f, 30.0f));
    const Camera& camera = rig.scene.cameras[0];
    ShadowedComparison r = compareWithShadowsOff(rig, camera, rig.analytic(camera), 0.5f);
    EXPECT_GT(r.litCompared, 30000);
    EXPECT_GT(r.shadowCompared, 1500);
    EXPECT_EQ(r.litChanged, 0) << "lit pixels changed by turning shadows on";
    EXPECT_EQ(r.notAmbient, 0);
}

// Alpha-masked casters (glTF MASK) are drawn into the shadow maps by their own program (the texture read and the
// discard; render/shadows/shadow_map_pass.h), the others by one without fragment work: a masked box whose alpha is
// above its cutoff casts the analytic shadow, one below it casts none (the G-buffer drops it too).
TEST(Shadows, AlphaMaskedCastersShadowWhatTheyDraw) {
    ShadowRig rig({{-0.5, 1.0, -0.6}, {0.5, 1.6, 0.6}}, sunAt(45.0f, 30.0f));
    const Camera& camera = rig.scene.cameras[0];
    std::vector<int> classes = rig.analytic(camera);
    rig.scene.materials[1].alphaCutoff = 0.5f;
    rig.scene.materials[1].baseColor.w = 0.9f;
    BoundaryCheck kept = checkBoundary(classes, rig.visibility(RenderSettings{}, camera), rig.size);
    EXPECT_GT(kept.shadowedPixels, 2000);
    EXPECT_EQ(kept.misplaced, 0) << "kept masked caster: first misplaced pixel at (" << kept.firstX << ", "
                                 << kept.firstY << ")";
    rig.scene.materials[1].baseColor.w = 0.2f;
    RenderSettings redrawn;
    redrawn.apply("shadow.cache=0");   // the cached maps hold the kept caster (a material edit is no geometry change)
    std::vector<float> dropped = rig.visibility(redrawn, camera);
    int shadowed = 0, inAnalyticShadow = 0;
    for (int y = 0; y < rig.size; ++y)
        for (int x = 0; x < rig.size; ++x) {
            if (classes[size_t(y) * rig.size + size_t(x)] != kShadowed) continue;
            ++inAnalyticShadow;
            shadowed += ShadowRig::red(dropped, rig.size, x, y) < 0.5f;
        }
    EXPECT_GT(inAnalyticShadow, 2000);
    EXPECT_EQ(shadowed, 0) << "a caster below its alpha cutoff still shadows";
}

// Makes the rig's plane glinty metal (no diffuse) without ambient, so that inside a shadow only the light could add
// radiance, and checks for every glint method: radiance exactly 0 in the shadowed pixels 3 px from the analytic
// boundary, > 0 there with shadows off (else the check proves nothing).
void expectNoGlintRadianceInShadow(ShadowRig& rig, const Camera& camera, const std::vector<int>& classes) {
    rig.scene.materials[0].glinty = true;
    rig.scene.materials[0].metallic = 1.0f;
    rig.scene.materials[0].alpha = 0.5f;
    rig.scene.skyColor = glm::vec3(0.0f);
    for (const std::string method : {"deliot2023", "zirr2016", "kemppinen2025", "wang2020"}) {
        RenderSettings on;
        on.method = method;
        RenderSettings off = on;
        off.apply("shadow.enabled=0");
        std::vector<float> with = rig.render(on, camera), without = rig.render(off, camera);
        double inShadow = 0.0, withoutShadows = 0.0;
        int pixels = 0;
        for (int y = 0; y < rig.size; ++y)
            for (int x = 0; x < rig.size; ++x) {
                if (classes[size_t(y) * rig.size + size_t(x)] != kShadowed || nearBoundary(classes, rig.size, x, y, 3))
                    continue;
                size_t i = (size_t(y) * rig.size + size_t(x)) * 4;
                ++pixels;
                inShadow += with[i] + with[i + 1] + with[i + 2];
                withoutShadows += without[i] + without[i + 1] + without[i + 2];
            }
        EXPECT_GT(pixels, 500) << method;
        EXPECT_GT(withoutShadows, 0.0) << method << ": no glints there even without shadows (the test proves nothing)";
        EXPECT_EQ(inShadow, 0.0) << method << ": glint radiance inside the shadow";
    }
}

TEST(Shadows, GlintyPlaneHasNoGlintRadianceInShadow) {
    ShadowRig rig({{-0.8, 1.0, -0.8}, {0.8, 1.3, 0.8}}, sunAt(35.0f, 30.0f));
    rig.size = 128;
    const Camera& camera = rig.scene.cameras[0];
    expectNoGlintRadianceInShadow(rig, camera, rig.analytic(camera));
}

// Sub-pixel position (x) where visibility crosses 0.5 going right along row y, searching from x0; -1 if none.
double edgeCrossing(const std::vector<float>& visibility, int size, int y, int x0) {
    for (int x = x0; x + 1 < size; ++x) {
        float a = ShadowRig::red(visibility, size, x, y), b = ShadowRig::red(visibility, size, x + 1, y);
        if ((a - 0.5f) * (b - 0.5f) <= 0.0f && a != b) return x + (0.5 - a) / (b - a);
    }
    return -1.0;
}

TEST(Shadows, SubTexelCameraTranslationDoesNotMoveTheShadowEdge) {
    // A wide plane (no cascade is clipped by the scene's bounds), one cascade of 256 texels over 15 m: a texel
    // is 9.3 cm, 3.3 px here. The camera moves by exactly one image pixel on the ground (2.84 cm, a third of a
    // texel), and the cascades are re-fitted every frame (shadow.cache=0): with snapping, the map samples the
    // world on the same texel grid and the edge moves with the ground, by exactly one pixel.
    ShadowRig rig({{-0.5, 1.0, -0.6}, {0.5, 1.6, 0.6}}, sunAt(45.0f, 30.0f), 200.0f);
    RenderSettings settings;
    for (const char* s : {"shadow.cache=0", "shadow.cascades=1", "shadow.map_size=256", "shadow.distance=15"})
        settings.apply(s);
    Camera camera = rig.scene.cameras[0];
    const float pixelOnGround = 2.0f * 10.0f * std::tan(glm::radians(20.0f)) / float(rig.size);
    double worst = 0.0;
    int rows = 0;
    for (int step = 0; step < 3; ++step) {
        Camera moved = camera;
        moved.position.x += pixelOnGround;
        moved.target.x += pixelOnGround;
        std::vector<float> a = rig.visibility(settings, camera), b = rig.visibility(settings, moved);
        for (int y = 60; y < 200; ++y) {
            double ea = edgeCrossing(a, rig.size, y, 0), eb = edgeCrossing(b, rig.size, y, 0);
            if (ea < 0.0 || eb < 0.0) continue;
            ++rows;
            worst = std::max(worst, std::abs((ea - 1.0) - eb));   // the ground moved one pixel left
        }
        camera = moved;
    }
    std::printf("[ shadow edge ] largest move against the ground: %.3f px over %d rows\n", worst, rows);
    EXPECT_GT(rows, 100) << "the shadow's left edge should cross most rows of the band";
    EXPECT_LE(worst, 0.5) << "the shadow edge moved against the ground by " << worst << " px";
}

TEST(Shadows, StillCameraRendersNoShadowViewAfterTheFirstFrame) {
    Light lantern;
    lantern.type = LightType::Point;
    lantern.vector = {0.5f, 3.0f, 0.5f};
    lantern.intensity = 4.0f;
    ShadowRig rig({{-0.5, 1.0, -0.6}, {0.5, 1.6, 0.6}}, sunAt(45.0f, 30.0f));
    rig.scene.lights.push_back(lantern);
    Camera camera = rig.scene.cameras[0];
    auto rendered = [&](const Camera& c) {
        rig.render(RenderSettings{}, c);
        const ShadowMaps::Stats& s = rig.renderer->shadowMaps().stats();
        return glm::ivec2(s.sunViewsRendered, s.localViewsRendered);
    };
    EXPECT_EQ(rendered(camera), glm::ivec2(3, 6)) << "first frame: three cascades and six cube faces";
    EXPECT_EQ(rendered(camera), glm::ivec2(0, 0)) << "still camera";
    Camera nudged = camera;
    nudged.position.x += 0.05f;
    nudged.target.x += 0.05f;
    EXPECT_EQ(rendered(nudged), glm::ivec2(0, 0)) << "a 5 cm move stays inside the cached cascades' margin";
    Camera far = camera;
    far.position.x += 5.0f;
    far.target.x += 5.0f;
    glm::ivec2 afterMove = rendered(far);
    EXPECT_GT(afterMove.x, 0) << "a 5 m move re-renders the near cascades";
    EXPECT_EQ(afterMove.y, 0) << "the point light's faces do not depend on the camera";
    rig.scene.lights[1].vector.x += 0.1f;
    EXPECT_EQ(rendered(far), glm::ivec2(0, 6)) << "a moved lantern re-renders its faces only";
    rig.scene.lights[0].vector = sunAt(40.0f, 30.0f).vector;
    EXPECT_EQ(rendered(far), glm::ivec2(3, 0)) << "a moved sun re-renders its cascades only";
    RenderSettings uncached;
    uncached.apply("shadow.cache=0");
    rig.render(uncached, far);
    EXPECT_EQ(rig.renderer->shadowMaps().stats().sunViewsRendered, 3);
}

// The shadow mask compiles each layer's program for the filters of its four slots (render/shadows/shadow_mask_pass.h):
// a slot must get the filter the generic shader would pick from the light (cascades for the sun, PCF for a point or
// spot light without a radius, soft shadows for one with a radius and for area lights), in the GPU's light order
// (punctual lights first, then area lights), and empty slots none. The other tests of this file and
// AreaLights.SoftShadowPenumbraGrowsWithTheLightSize check each filter's image.
TEST(Shadows, MaskLayersCompileTheFiltersOfTheirLights) {
    Light sphere;
    sphere.type = LightType::Sphere;
    sphere.vector = {-1.0f, 3.0f, 0.0f};
    sphere.radius = 0.2f;
    sphere.intensity = 50.0f;
    Light point;
    point.type = LightType::Point;
    point.vector = {0.5f, 3.0f, 0.5f};
    point.intensity = 4.0f;
    Light sizedPoint = point;
    sizedPoint.vector.x = -0.5f;
    sizedPoint.radius = 0.1f;
    Light spot = point;
    spot.type = LightType::Spot;
    spot.spotDirection = {0.0f, -1.0f, 0.0f};
    spot.outerConeAngle = 0.5f;
    ShadowRig rig({{-0.5, 1.0, -0.6}, {0.5, 1.6, 0.6}}, sunAt(45.0f, 30.0f));
    rig.scene.lights = {sphere, rig.scene.lights[0], point, sizedPoint, spot};
    rig.render(RenderSettings{}, rig.scene.cameras[0]);
    const ShadowMaps& maps = rig.renderer->shadowMaps();
    ASSERT_EQ(maps.maskLayers(), 2);
    const int cascades = int(ShadowFilter::Cascades), pcf = int(ShadowFilter::Pcf), pcss = int(ShadowFilter::Pcss);
    EXPECT_EQ(maps.maskLayerFilters(0), glm::ivec4(cascades, pcf, pcss, pcf)) << "sun, point, sized point, spot";
    EXPECT_EQ(maps.maskLayerFilters(1), glm::ivec4(pcss, 0, 0, 0)) << "the sphere light last, then empty slots";
}

TEST(Shadows, PointLightCubeShadowMatchesTheCentralProjectionAcrossFaces) {
    // A lantern 1.2 m above the plane and a box beside it: the shadow on the ground runs from the -y face of the
    // cube (below the light) into the +x face (beyond |x| = 1.2 m).
    Light lantern;
    lantern.type = LightType::Point;
    lantern.vector = {0.0f, 1.2f, 0.0f};
    lantern.intensity = 3.0f;
    ShadowRig rig({{0.5, 0.3, -0.3}, {1.0, 0.9, 0.3}}, lantern);
    Camera camera = rig.scene.cameras[0];
    camera.position = {2.0f, 7.0f, 0.0f};
    camera.target = {2.0f, 0.0f, 0.0f};
    camera.verticalFovDegrees = 45.0f;
    std::vector<int> classes = rig.analytic(camera);
    BoundaryCheck check = checkBoundary(classes, rig.visibility(RenderSettings{}, camera), rig.size);
    EXPECT_GT(check.shadowedPixels, 2000);
    EXPECT_EQ(check.misplaced, 0) << "first misplaced pixel at (" << check.firstX << ", " << check.firstY << ")";
    // Both faces hold part of the shadow.
    int below = 0, beyond = 0;
    for (int y = 0; y < rig.size; ++y)
        for (int x = 0; x < rig.size; ++x) {
            if (classes[size_t(y) * rig.size + size_t(x)] != kShadowed) continue;
            Ray ray = cameraRay(camera, rig.size, rig.size, x + 0.5, y + 0.5);
            double gx = ray.origin.x - ray.origin.y / ray.direction.y * ray.direction.x;
            (std::abs(gx) < 1.2 ? below : beyond) += 1;
        }
    EXPECT_GT(below, 100);
    EXPECT_GT(beyond, 100);
}

Light spotAt(const glm::vec3& position, float outerConeDegrees) {
    Light spot;
    spot.type = LightType::Spot;
    spot.vector = position;
    spot.spotDirection = {0.0f, -1.0f, 0.0f};
    spot.innerConeAngle = glm::radians(outerConeDegrees * 0.8f);
    spot.outerConeAngle = glm::radians(outerConeDegrees);
    spot.intensity = 6.0f;
    return spot;
}

TEST(Shadows, SpotLightShadowMatchesTheCentralProjectionAndIsCached) {
    // A spot 3 m above the plane shining down, a box off its axis. 40 degrees: one perspective view fitted to the
    // cone; 70 degrees (wider than kMaxSpotViewHalfAngle): the six faces of a cube, by the point lights' code.
    for (float cone : {40.0f, 70.0f}) {
        SCOPED_TRACE(cone);
        ShadowRig rig({{0.3, 1.0, -0.4}, {0.9, 1.6, 0.4}}, spotAt({0.0f, 3.0f, 0.0f}, cone));
        const Camera& camera = rig.scene.cameras[0];
        std::vector<int> classes = rig.analytic(camera);
        BoundaryCheck check = checkBoundary(classes, rig.visibility(RenderSettings{}, camera), rig.size);
        EXPECT_GT(check.shadowedPixels, 2000);
        EXPECT_GT(check.litPixels, 10000);
        EXPECT_EQ(check.misplaced, 0) << "first misplaced pixel at (" << check.firstX << ", " << check.firstY << ")";
        const int views = cone < 60.0f ? 1 : 6;
        EXPECT_EQ(rig.renderer->shadowMaps().stats().views, views);
        // Cached: a still frame renders nothing; turning the spot re-renders its one view (a cube does not depend
        // on the direction); moving it re-renders every view.
        rig.render(RenderSettings{}, camera);
        EXPECT_EQ(rig.renderer->shadowMaps().stats().localViewsRendered, 0) << "still spot re-rendered";
        rig.scene.lights[0].spotDirection = glm::normalize(glm::vec3(0.1f, -1.0f, 0.0f));
        rig.render(RenderSettings{}, camera);
        EXPECT_EQ(rig.renderer->shadowMaps().stats().localViewsRendered, views == 1 ? 1 : 0) << "turned spot";
        rig.scene.lights[0].vector.x += 0.1f;
        rig.render(RenderSettings{}, camera);
        EXPECT_EQ(rig.renderer->shadowMaps().stats().localViewsRendered, views) << "moved spot not re-rendered";
    }
}

TEST(Shadows, SpotShadowLeavesTheLitSideAndHoldsNoGlints) {
    ShadowRig rig({{0.3, 1.0, -0.4}, {0.9, 1.6, 0.4}}, spotAt({0.0f, 3.0f, 0.0f}, 40.0f));
    const Camera& camera = rig.scene.cameras[0];
    std::vector<int> classes = rig.analytic(camera);
    // The spot alone (shadow-mask slot 0), then after four black point lights that take slots 0-3, so that its
    // visibility comes from the mask's second layer.
    for (int darkLights : {0, 4}) {
        SCOPED_TRACE(darkLights);
        rig.scene.lights.resize(1);
        for (int k = 0; k < darkLights; ++k) {
            Light dark;
            dark.type = LightType::Point;
            dark.vector = {float(k) - 1.5f, 2.0f, -2.0f};
            dark.intensity = 0.0f;
            rig.scene.lights.insert(rig.scene.lights.begin(), dark);
        }
        ShadowedComparison r = compareWithShadowsOff(rig, camera, classes, 0.0f);
        rig.render(RenderSettings{}, camera);   // shadows on again, to read the mask's layer count
        EXPECT_EQ(rig.renderer->shadowMaps().maskLayers(), darkLights == 0 ? 1 : 2);
        EXPECT_GT(r.litCompared, 10000);
        EXPECT_GT(r.shadowCompared, 1500);
        EXPECT_EQ(r.litChanged, 0) << "lit pixels changed by the spot's shadow";
        EXPECT_EQ(r.notAmbient, 0) << "shadowed pixels hold more than the ambient";
    }
    rig.scene.lights.resize(1);
    rig.scene.lights[0] = spotAt({0.0f, 3.0f, 0.0f}, 40.0f);

    expectNoGlintRadianceInShadow(rig, camera, classes);
}

TEST(Shadows, HalfResolutionMaskKeepsTheBoundaryAndItsSamples) {
    // shadow.half_res=1 filters the maps at every second pixel in x and y and interpolates the rest by depth and
    // plane: the boundary stays within 2 px of the analytic one, the sample pixels are the full-resolution mask's,
    // and pixels away from the boundary are exactly lit or shadowed.
    ShadowRig rig({{-0.5, 1.0, -0.6}, {0.5, 1.6, 0.6}}, sunAt(45.0f, 30.0f));
    const Camera& camera = rig.scene.cameras[0];
    std::vector<int> classes = rig.analytic(camera);
    RenderSettings half;
    half.apply("shadow.half_res=1");
    std::vector<float> full = rig.visibility(RenderSettings{}, camera), halved = rig.visibility(half, camera);
    EXPECT_EQ(rig.renderer->shadowMaps().maskSize(), glm::ivec2(rig.size / 2));
    BoundaryCheck check = checkBoundary(classes, halved, rig.size);
    EXPECT_GT(check.shadowedPixels, 2000);
    EXPECT_EQ(check.misplaced, 0) << "first misplaced pixel at (" << check.firstX << ", " << check.firstY << ")";
    int samples = 0, samplesDiffer = 0, interior = 0, interiorNotExact = 0, interpolatedDiffer = 0;
    for (int y = 0; y < rig.size; ++y)
        for (int x = 0; x < rig.size; ++x) {
            int c = classes[size_t(y) * rig.size + size_t(x)];
            if (c == kExcluded) continue;
            float a = ShadowRig::red(full, rig.size, x, y), b = ShadowRig::red(halved, rig.size, x, y);
            if (x % 2 == 0 && y % 2 == 0) {
                ++samples;
                samplesDiffer += std::abs(a - b) > 1e-6f;
            } else {
                interpolatedDiffer += a != b;
            }
            if (!nearBoundary(classes, rig.size, x, y, 3)) {
                ++interior;
                interiorNotExact += b != (c == kLit ? 1.0f : 0.0f);
            }
        }
    EXPECT_GT(samples, 10000);
    EXPECT_EQ(samplesDiffer, 0) << "sample pixels differ from the full-resolution mask";
    EXPECT_GT(interpolatedDiffer, 0) << "no interpolated pixel differs: the half-resolution mask was not used";
    EXPECT_GT(interior, 40000);
    EXPECT_EQ(interiorNotExact, 0);
}

}  // namespace
}  // namespace glimmer
