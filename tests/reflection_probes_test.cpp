// Reflection probes (render/probes/reflection_probes.h): a mirror sphere next to a coloured wall reflects the wall on
// the side facing it and the sky on the far side; the white furnace holds with probes on; a second frame with
// nothing changed does not re-capture; the proxy box fit (CPU).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "core/files.h"
#include "platform/context.h"
#include "render/gpu_scene.h"
#include "render/probes/reflection_probe_placement.h"
#include "render/probes/reflection_probes.h"
#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/mesh_builder.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(ReflectionProbes, GlContext);

namespace glimmer {
namespace {

constexpr int kSize = 128;

struct ProbeRig {
    std::unique_ptr<GLContext> context = createHeadlessContext(Backend::Egl);
    Scene scene;
    std::unique_ptr<GpuScene> gpu;
    std::unique_ptr<Renderer> renderer;
    std::string method = "smooth";   // of every render()

    void finish() {
        Camera camera;
        camera.name = "front";
        camera.position = {0.0f, 0.0f, 4.0f};
        camera.target = {0.0f, 0.0f, 0.0f};
        camera.verticalFovDegrees = 45.0f;
        scene.cameras = {camera};
        gpu = std::make_unique<GpuScene>(scene);
        renderer = std::make_unique<Renderer>(defaultShaderDir(), RenderSettings{});
    }
    ~ProbeRig() {
        context->makeCurrent();
        renderer.reset();
        gpu.reset();
    }
    std::vector<float> render(const std::vector<std::string>& sets, bool measure = false) {
        RenderSettings settings;
        settings.method = method;
        settings.apply("probes.face_size=64");
        // Ambient occlusion off: it darkens the environment term (probe reflections included) beside the wall,
        // which these tests of the probes themselves do not model.
        settings.apply("ao.enabled=0");
        for (const std::string& s : sets) settings.apply(s);
        gpu->updateMaterialsAndLights(scene);
        renderer->setSettings(settings);
        renderer->renderView(scene, *gpu, scene.cameras[0], kSize, kSize, measure);
        return renderer->readHdr();
    }
    // The pixel that shows world point p (GL rows, bottom first).
    glm::ivec2 pixelOf(glm::vec3 p) const {
        const Camera& c = scene.cameras[0];
        glm::vec4 clip = c.projection(1.0f) * c.view() * glm::vec4(p, 1.0f);
        glm::vec2 ndc = glm::vec2(clip) / clip.w;
        return glm::ivec2((ndc * 0.5f + 0.5f) * float(kSize));
    }
};

glm::vec3 pixel(const std::vector<float>& hdr, glm::ivec2 p) {
    const float* v = &hdr[(size_t(p.y) * kSize + size_t(p.x)) * 4];
    return {v[0], v[1], v[2]};
}

// A mirror sphere (metal, f0 = 1, alpha 0.02) at the origin, a red Lambertian wall at x = 2.5 facing it lit by the
// sun, a grey constant sky. Seen from +z, the sphere point with normal (1, 0, 1)/sqrt 2 mirrors the view ray into
// +x, onto the wall; the point with normal (-1, 0, 1)/sqrt 2 mirrors it into -x, the open sky.
void buildWallScene(Scene& scene) {
    scene.name = "probe-wall";
    scene.environment = "constant:0.3,0.3,0.3";
    scene.meshes.push_back(makeUvSphere(1.0f, 96, 48));
    MeshBuilder wall("wall");
    wall.quad({2.5f, -5.0f, -5.0f}, {2.5f, 5.0f, -5.0f}, {2.5f, 5.0f, 5.0f}, {2.5f, -5.0f, 5.0f}, {-1, 0, 0}, {});
    scene.meshes.push_back(wall.finish());
    Material mirror;
    mirror.baseColor = glm::vec4(1.0f);
    mirror.metallic = 1.0f;
    mirror.alpha = 0.02f;
    Material red;
    red.baseColor = glm::vec4(0.8f, 0.1f, 0.1f, 1.0f);
    red.metallic = 0.0f;
    red.alpha = 0.8f;
    scene.materials = {mirror, red};
    scene.instances = {{0, 0, glm::mat4(1.0f)}, {1, 1, glm::mat4(1.0f)}};
    scene.lights.push_back({LightType::Directional, glm::normalize(glm::vec3(-1.0f, 0.5f, 0.3f)), {1, 1, 1}, 2.0f});
}

TEST(ReflectionProbes, MirrorSphereReflectsTheWallOnTheSideFacingIt) {
    ProbeRig rig;
    buildWallScene(rig.scene);
    rig.finish();
    const glm::ivec2 nearSide = rig.pixelOf(glm::normalize(glm::vec3(1, 0, 1)));
    const glm::ivec2 farSide = rig.pixelOf(glm::normalize(glm::vec3(-1, 0, 1)));

    std::vector<float> with = rig.render({});
    ASSERT_EQ(rig.renderer->probes().probes().size(), 1u);
    std::vector<float> without = rig.render({"probes.enabled=0"});
    // The wall's own radiance, seen head-on from the sphere's side (uniform: flat Lambert under a directional light
    // and a constant sky).
    rig.scene.cameras[0].position = {1.5f, 0.0f, 0.0f};
    rig.scene.cameras[0].target = {2.5f, 0.0f, 0.0f};
    std::vector<float> wallView = rig.render({"probes.enabled=0"});
    const glm::vec3 wall = pixel(wallView, {kSize / 2, kSize / 2});
    ASSERT_GT(wall.x, 4.0f * wall.y);

    glm::vec3 nearWith = pixel(with, nearSide), farWith = pixel(with, farSide);
    glm::vec3 nearWithout = pixel(without, nearSide), farWithout = pixel(without, farSide);
    // Facing the wall: its red (f0 = 1 and a near-mirror lobe: A + B ~ 1), within 10% (probe resolution 64,
    // the lobe blends levels 0 and 1 of the prefiltered probe).
    EXPECT_GT(nearWith.x, 3.0f * nearWith.y) << nearWith.x << " " << nearWith.y;
    EXPECT_NEAR(nearWith.x, wall.x, 0.1f * wall.x);
    EXPECT_NEAR(nearWith.y, wall.y, 0.1f * wall.x);
    // The far side sees only the grey sky (its probe texels are sky, coverage 0): grey, as without probes.
    EXPECT_NEAR(farWith.x, farWith.y, 0.02f * farWith.y);
    EXPECT_NEAR(farWith.x, farWithout.x, 0.01f * farWithout.x);
    // Control: without probes the near side shows the grey sky too, so the checks above can fail.
    EXPECT_NEAR(nearWithout.x, nearWithout.y, 0.02f * nearWithout.y);
}

// Two spheres under a constant sky and no lights: a white metal one (its probe sees the other) and a white
// dielectric one (a white furnace: it returns exactly the sky's radiance). The probe then sees L in every
// direction, so with probes on every pixel matches the render without them.
TEST(ReflectionProbes, WhiteFurnaceIsUnchangedWithProbes) {
    ProbeRig rig;
    rig.scene.name = "probe-furnace";
    rig.scene.environment = "constant:0.6,0.8,1.0";
    rig.scene.meshes.push_back(makeUvSphere(1.0f, 96, 48));
    Material metal;
    metal.baseColor = glm::vec4(1.0f);
    metal.metallic = 1.0f;
    metal.alpha = 0.1f;
    Material white;
    white.baseColor = glm::vec4(1.0f);
    white.metallic = 0.0f;
    white.alpha = 0.3f;
    rig.scene.materials = {metal, white};
    rig.scene.instances = {{0, 0, glm::translate(glm::mat4(1.0f), glm::vec3(-1.1f, 0, 0))},
                           {0, 1, glm::translate(glm::mat4(1.0f), glm::vec3(1.1f, 0, 0))}};
    rig.finish();
    std::vector<float> with = rig.render({});
    ASSERT_EQ(rig.renderer->probes().probes().size(), 1u);
    // The other sphere covers ~5% of the sphere of directions (3.4% of the cube texels, measured).
    EXPECT_GT(rig.renderer->probes().probes()[0].coverage, 0.02f);
    std::vector<float> without = rig.render({"probes.enabled=0"});
    double worst = 0.0;
    for (size_t i = 0; i < with.size(); i += 4)
        for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(with[i + size_t(c)]));
            worst = std::max(worst, std::abs(double(with[i + size_t(c)]) - without[i + size_t(c)]) /
                                        std::max(double(without[i + size_t(c)]), 1e-3));
        }
    EXPECT_LT(worst, 0.02);
}

TEST(ReflectionProbes, NotRecapturedWhenNothingChanged) {
    ProbeRig rig;
    buildWallScene(rig.scene);
    rig.finish();
    auto ran = [&](const char* name) {
        for (const PassTiming& t : rig.renderer->passTimings())
            if (t.name == name) return true;
        return false;
    };
    // Captured, or read from the disk cache a previous run stored (ProbeDiskCache below).
    auto updates = [&] { return rig.renderer->probes().captures() + rig.renderer->probes().diskLoads(); };
    rig.render({}, true);
    EXPECT_EQ(updates(), 1);
    EXPECT_TRUE(ran("probes.capture") || ran("probes.load"));
    rig.render({}, true);
    EXPECT_EQ(updates(), 1);
    EXPECT_FALSE(ran("probes.capture") || ran("probes.load"));
    // Settings a capture does not read (image pipeline, passes a capture turns off) keep the probes...
    rig.render({"exposure=2", "tonemap=agx", "aa=taa", "bloom.strength=0.5", "shadow.filter_radius=3", "ao.radius=2"},
               true);
    EXPECT_EQ(updates(), 1) << "a setting the capture never reads re-captured the probes";
    // ...one it reads does not.
    rig.render({"material.alpha=0.2"}, true);
    EXPECT_EQ(updates(), 2) << "a material change kept stale probes";
    rig.render({}, true);
    EXPECT_EQ(updates(), 3);
    // A moved wall is a change: captured (or read) again.
    rig.scene.instances[1].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0, 0));
    rig.render({}, true);
    EXPECT_EQ(updates(), 4);
    EXPECT_TRUE(ran("probes.capture") || ran("probes.load"));
}

// The split screen's second renderer (Renderer(root, settings, source)) reads the first one's probes and
// environment: nothing is captured or prepared again, and its image equals that of a renderer with probes of its own.
TEST(ReflectionProbes, SecondViewReadsTheFirstRenderersProbes) {
    ProbeRig rig;
    buildWallScene(rig.scene);
    rig.finish();
    rig.render({});
    const ReflectionProbes& probes = rig.renderer->probes();
    const int updates = probes.captures() + probes.diskLoads();
    ASSERT_EQ(updates, 1);
    ASSERT_FALSE(probes.probes().empty());

    RenderSettings settings = rig.renderer->settings();
    settings.method = "deliot2023";
    Renderer second(defaultShaderDir(), settings, *rig.renderer);
    second.renderView(rig.scene, *rig.gpu, rig.scene.cameras[0], kSize, kSize);
    EXPECT_EQ(&second.probes(), &probes);
    EXPECT_EQ(&second.environment(), &rig.renderer->environment());
    EXPECT_EQ(probes.captures() + probes.diskLoads(), updates) << "the second view captured the probes again";
    const std::vector<float> shared = second.readHdr();

    Renderer own(defaultShaderDir(), settings);
    own.renderView(rig.scene, *rig.gpu, rig.scene.cameras[0], kSize, kSize);
    EXPECT_EQ(own.probes().captures() + own.probes().diskLoads(), 1);
    const std::vector<float> reference = own.readHdr();
    ASSERT_EQ(shared.size(), reference.size());
    float worst = 0.0f;
    for (size_t i = 0; i < shared.size(); ++i) worst = std::max(worst, std::abs(shared[i] - reference[i]));
    EXPECT_LE(worst, 1e-4f) << "the shared probes render as the second renderer's own would";
    // The mirror's wall side shows the probes (red), so an unpublished probe block would fail above.
    const glm::vec3 wallSide = pixel(shared, rig.pixelOf(glm::vec3(1.0f, 0.0f, 1.0f) / std::sqrt(2.0f)));
    EXPECT_GT(wallSide.x, 2.0f * wallSide.y);
}

// The disk cache (reflection_probes.h): a second renderer reads the probes the first captured, and renders the same
// image; a damaged file, another scene or another environment is captured again, never read.
TEST(ReflectionProbes, DiskCacheGivesTheSameImageAndRejectsDamage) {
    const std::string dir = test::makeTempDir("probe-cache");
    const char* previous = std::getenv("GLIMMER_CACHE_DIR");
    const std::string restore = previous ? previous : "";
    setenv("GLIMMER_CACHE_DIR", dir.c_str(), 1);
    struct Restore {
        std::string value;
        ~Restore() { value.empty() ? unsetenv("GLIMMER_CACHE_DIR") : setenv("GLIMMER_CACHE_DIR", value.c_str(), 1); }
    } restoreAtExit{restore};
    std::vector<float> captured;
    {
        ProbeRig rig;
        buildWallScene(rig.scene);
        rig.finish();
        captured = rig.render({"probes.face_size=32"});
        EXPECT_EQ(rig.renderer->probes().captures(), 1);
        EXPECT_EQ(rig.renderer->probes().diskLoads(), 0);
    }
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().filename().string().rfind("probes_", 0) == 0) files.push_back(e.path());
    ASSERT_EQ(files.size(), 1u) << "one probe file stored";
    {
        ProbeRig rig;
        buildWallScene(rig.scene);
        rig.finish();
        std::vector<float> loaded = rig.render({"probes.face_size=32"});
        EXPECT_EQ(rig.renderer->probes().captures(), 0);
        EXPECT_EQ(rig.renderer->probes().diskLoads(), 1);
        EXPECT_EQ(loaded, captured) << "the cached probes render the same image";
        // Another scene (the wall moved) is not read from the file of this one.
        rig.scene.instances[1].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0, 0));
        rig.render({"probes.face_size=32"});
        EXPECT_EQ(rig.renderer->probes().captures(), 1);
    }
    {
        // One flipped bit in the payload (the checksum) and values a hostile writer made (NaN, checksum right).
        std::string bytes;
        {
            std::ifstream in(files[0], std::ios::binary);
            bytes.assign(std::istreambuf_iterator<char>(in), {});
        }
        std::string flipped = bytes;
        flipped[flipped.size() - 5] ^= 1;
        std::ofstream(files[0], std::ios::binary | std::ios::trunc) << flipped;
        ProbeRig rig;
        buildWallScene(rig.scene);
        rig.finish();
        EXPECT_EQ(rig.render({"probes.face_size=32"}), captured);
        EXPECT_EQ(rig.renderer->probes().diskLoads(), 0);
        EXPECT_EQ(rig.renderer->probes().captures(), 1);
    }
}

// The window's start (Renderer::RefinementPace): its first picture (Deferred) lights with a preview of a new
// environment and no probes, stores nothing in the disk cache and lists what waits; the frames after it (OnePerFrame)
// run one refinement step each (the environment's prefilter one walk a frame, then the probe capture, then the
// environment glints) and end on the very image a renderer that does everything in its first frame makes.
TEST(ReflectionProbes, PacedStartPreviewsThenRefinesOneStepAFrame) {
    const std::string dir = test::makeTempDir("paced-start");
    struct Variables {   // what this test sets, restored at its end
        std::vector<std::pair<std::string, std::string>> saved;
        void set(const char* name, const char* value) {
            const char* old = std::getenv(name);
            saved.push_back({name, old ? old : std::string("\x01")});
            value ? setenv(name, value, 1) : unsetenv(name);
        }
        ~Variables() {
            for (auto it = saved.rbegin(); it != saved.rend(); ++it)
                it->second == "\x01" ? unsetenv(it->first.c_str()) : setenv(it->first.c_str(), it->second.c_str(), 1);
        }
    } variables;
    variables.set("GLIMMER_CACHE_DIR", dir.c_str());
    variables.set("GLIMMER_ENV_CACHE", nullptr);
    variables.set("GLIMMER_PROBE_CACHE", nullptr);
    variables.set("GLIMMER_ENV_PREFILTER_REFINE", "2");   // 3.5x faster; this test judges the pacing, not the maps
    auto environmentFiles = [&] {
        int n = 0;
        for (const auto& e : std::filesystem::directory_iterator(dir))
            n += e.path().filename().string().rfind("environment", 0) == 0;
        return n;
    };
    ProbeRig rig;
    buildWallScene(rig.scene);
    rig.scene.environment = "";   // the procedural sky: rough lobes of the preview and the prefilter differ
    rig.method = "deliot2023";     // a method with environment glints
    rig.finish();
    rig.renderer->setRefinementPace(Renderer::RefinementPace::Deferred);
    const std::vector<float> first = rig.render({});
    EXPECT_FALSE(rig.renderer->environment().refined());
    EXPECT_TRUE(rig.renderer->probes().probes().empty());
    EXPECT_EQ(rig.renderer->probes().captures(), 0);
    EXPECT_EQ(environmentFiles(), 0) << "the preview was stored in the disk cache";
    const std::vector<std::string> all = rig.renderer->waitingRefinements();
    ASSERT_EQ(all.size(), 3u);
    EXPECT_EQ(all[0], "environment maps");
    EXPECT_EQ(all[1], "reflection probes");
    EXPECT_EQ(all[2], "environment glints");

    rig.renderer->setRefinementPace(Renderer::RefinementPace::OnePerFrame);
    std::vector<float> paced;
    // The prefilter one walk a frame ("environment maps k/n" while it lasts), then one step a frame.
    const int walks = rig.renderer->environment().refineProgress().second;
    int environmentFrames = 0;
    for (size_t done = 0; done < all.size();) {
        ASSERT_LT(environmentFrames, 12) << "the prefilter does not end";
        paced = rig.render({});
        const std::vector<std::string>& waiting = rig.renderer->waitingRefinements();
        if (!rig.renderer->environment().refined()) {
            ++environmentFrames;
            const auto [walked, count] = rig.renderer->environment().refineProgress();
            EXPECT_EQ(walked, environmentFrames) << "not one walk a frame";
            ASSERT_EQ(waiting.size(), all.size());
            EXPECT_EQ(waiting[0], "environment maps " + std::to_string(walked) + "/" + std::to_string(count));
            continue;
        }
        ++done;
        ASSERT_EQ(waiting.size(), all.size() - done) << "a frame did not run exactly one refinement";
        for (size_t i = 0; i < waiting.size(); ++i) EXPECT_EQ(waiting[i], all[done + i]);
    }
    EXPECT_GT(environmentFrames, 1) << "the prefilter ran in one frame";
    EXPECT_EQ(walks, 1) << "progress before the first walk";
    EXPECT_TRUE(rig.renderer->environment().refined());
    EXPECT_EQ(environmentFiles(), 1) << "the refined maps were not stored";
    EXPECT_EQ(rig.renderer->probes().captures(), 1);
    ASSERT_EQ(rig.renderer->probes().probes().size(), 1u);

    // Everything in the first frame, from scratch (no disk cache).
    variables.set("GLIMMER_ENV_CACHE", "0");
    variables.set("GLIMMER_PROBE_CACHE", "0");
    rig.renderer = std::make_unique<Renderer>(defaultShaderDir(), RenderSettings{});
    const std::vector<float> reference = rig.render({});
    ASSERT_EQ(paced.size(), reference.size());
    size_t differing = 0, previewDiffering = 0;
    for (size_t i = 0; i < paced.size(); ++i) {
        differing += paced[i] != reference[i];
        previewDiffering += first[i] != reference[i];
    }
    EXPECT_EQ(differing, 0u) << "the paced frames end on another image";
    // Control: the first picture (preview, no probes) is another image, so the check above can fail.
    EXPECT_GT(previewDiffering, reference.size() / 20);
}

// CPU: the proxy box takes the median hit distance of each face, the scene bounds where the face saw mostly sky,
// and never cuts into the influence box.
TEST(ReflectionProbePlacement, ProxyBoxFitsTheMedianHitOfEachFace) {
    const float inf = std::numeric_limits<float>::infinity();
    std::array<std::vector<float>, 6> d;
    d[0] = {2.0f, 2.5f, 3.0f, 9.0f};   // +x: median of 4 hits (upper middle) = 3
    d[1] = {inf, inf, inf, 1.0f};      // -x: mostly sky -> limits
    d[2] = {0.5f, 0.5f, 0.5f, inf};    // +y: 0.5, but the influence box reaches 1 -> 1
    d[3] = {1.5f, 1.5f, 1.5f, 1.5f};   // -y: floor 1.5 below
    d[4] = {inf, inf, inf, inf};       // +z: sky
    d[5] = {4.0f, 4.0f, inf, inf};     // -z: half sky -> limits
    Box limits{{-10, -10, -10}, {10, 10, 10}};
    Box influence{{-0.5f, -0.5f, -0.5f}, {0.5f, 1.0f, 0.5f}};
    Box box = fitProxyBox({0, 0, 0}, d, limits, influence);
    EXPECT_FLOAT_EQ(box.max.x, 3.0f);
    EXPECT_FLOAT_EQ(box.min.x, -10.0f);
    EXPECT_FLOAT_EQ(box.max.y, 1.0f);
    EXPECT_FLOAT_EQ(box.min.y, -1.5f);
    EXPECT_FLOAT_EQ(box.max.z, 10.0f);
    EXPECT_FLOAT_EQ(box.min.z, -10.0f);
}

TEST(ReflectionProbePlacement, OneProbePerMetallicInstance) {
    Scene scene;
    scene.meshes.push_back(makeUvSphere(1.0f, 32, 16));
    Material metal, stone;
    metal.metallic = 0.8f;
    stone.metallic = 0.0f;
    scene.materials = {metal, stone};
    scene.instances = {{0, 1, glm::mat4(1.0f)},
                       {0, 0, glm::translate(glm::mat4(1.0f), glm::vec3(3, 0, 0))},
                       {0, 0, glm::translate(glm::mat4(1.0f), glm::vec3(-3, 0, 0))}};
    std::vector<ProbePlacement> probes = placeReflectionProbes(scene, 8);
    ASSERT_EQ(probes.size(), 2u);
    EXPECT_EQ(probes[0].excludedInstance, 1);
    EXPECT_NEAR(glm::length(probes[0].position - glm::vec3(3, 0, 0)), 0.0f, 1e-3f);   // closed: at the centroid
    EXPECT_TRUE(probes[0].influence.contains({3.0f, 1.0f, 0.0f}));    // the object's surface is inside
    EXPECT_FALSE(probes[0].influence.contains({0.0f, 0.0f, 0.0f}));   // the stone sphere is not
    EXPECT_EQ(placeReflectionProbes(scene, 1).size(), 1u);

    // A flat metal plate facing +x (a relief on a wall): captured in front of it, not on its surface.
    MeshBuilder plate("plate");
    plate.quad({0, -1, -1}, {0, 1, -1}, {0, 1, 1}, {0, -1, 1}, {1, 0, 0}, {});
    scene.meshes.push_back(plate.finish());
    scene.instances = {{1, 0, glm::mat4(1.0f)}};
    EXPECT_TRUE(placeReflectionProbes(scene, 8).empty());   // alone: it would see only the sky
    scene.instances.push_back({0, 1, glm::translate(glm::mat4(1.0f), glm::vec3(5, 0, 0))});
    probes = placeReflectionProbes(scene, 8);
    ASSERT_EQ(probes.size(), 1u);
    EXPECT_NEAR(probes[0].position.x, probes[0].fade, 1e-3f);
    EXPECT_TRUE(probes[0].influence.contains(probes[0].position));
}

}  // namespace
}  // namespace glimmer
