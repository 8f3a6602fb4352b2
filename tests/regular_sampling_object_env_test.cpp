// Sec. 3 of "Real-time Rendering of Glossy Materials with Regular Sampling" (CGI 2014): per-object environment
// maps rendered at the object's centroid, face orientation, re-rendering exactly when the scene changes, and the
// reflection (the map's content) following a moved neighbour.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "core/files.h"
#include "core/image_io.h"
#include "environment/ibl/object_environment.h"
#include "render/renderer_capture.h"
#include "platform/context.h"
#include "reference/environment_reference.h"
#include "render/aov.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "render/settings.h"
#include "scene/scene_loader.h"

namespace glimmer::ibl {
namespace {

bool reddish(glm::vec3 c) { return c.x > 0.05f && c.x > 3.0f * c.y && c.x > 3.0f * c.z; }

// Number of red texels on a face.
int redTexels(const std::vector<float>& face) {
    int n = 0;
    for (size_t i = 0; i + 3 < face.size(); i += 4) n += reddish({face[i], face[i + 1], face[i + 2]});
    return n;
}

// The built-in sphere scene plus a red diffuse copy of its glossy sphere (the last instance): the neighbour.
struct SphereAndNeighbour {
    Scene scene;
    uint32_t glossy = 0;   // instance index of the glossy sphere
    glm::vec3 centre{};    // its centroid
    // A transform for the neighbour: the glossy sphere scaled by `scale` about its centre, then moved by `offset`.
    glm::mat4 place(glm::vec3 offset, float scale) const {
        return glm::translate(glm::mat4(1.0f), centre + offset) * glm::scale(glm::mat4(1.0f), glm::vec3(scale)) *
               glm::translate(glm::mat4(1.0f), -centre);
    }
};

SphereAndNeighbour sphereWithRedNeighbour(glm::vec3 offset, float scale) {
    SphereAndNeighbour r;
    r.scene = loadScene("sphere");
    for (uint32_t i = 0; i < r.scene.instances.size(); ++i)
        if (r.scene.materials[r.scene.instances[i].material].name == "sphere") r.glossy = i;
    Material red;
    red.name = "red";
    red.baseColor = {1.0f, 0.0f, 0.0f, 1.0f};
    red.metallic = 0.0f;
    r.scene.materials.push_back(red);
    r.centre = instanceCentroid(r.scene, r.scene.instances[r.glossy]);
    Instance neighbour = r.scene.instances[r.glossy];
    neighbour.material = uint32_t(r.scene.materials.size() - 1);
    neighbour.transform = r.place(offset, scale);
    r.scene.instances.push_back(neighbour);
    return r;
}

TEST(RegularSamplingObjectEnvironment, MapsFollowTheSceneAndRerenderOnlyOnChange) {
    auto context = createHeadlessContext(Backend::Egl);
    // A red diffuse neighbour 1.5 units along +x of the glossy sphere, off-axis, so a flipped or rotated face would
    // be caught.
    const glm::vec3 offset(1.5f, 0.6f, -0.4f);
    SphereAndNeighbour rig = sphereWithRedNeighbour(offset, 0.5f);
    Scene& scene = rig.scene;
    const uint32_t glossy = rig.glossy;
    const glm::vec3 centre = rig.centre;
    scene.materials.back().alpha = 0.5f;

    const int size = 32;
    ObjectEnvironmentMaps maps(defaultShaderDir(), size, PyramidFilter::Gauss4);
    RendererCapture capture(defaultShaderDir());
    EXPECT_EQ(maps.update(scene, {glossy}, capture), 1);
    EXPECT_NEAR(glm::length(maps.centroid(0) - centre), 0.0f, 1e-4f);
    // Face order +X, -X, ...: the neighbour fills the centre of +X, not of -X.
    EXPECT_GT(redTexels(maps.readFace(0, 0)), 10);
    EXPECT_EQ(redTexels(maps.readFace(0, 1)), 0);
    // Orientation: the red texels' directions (GL cube conventions, envref::cubeTexelDirection) point at the
    // neighbour's centre within its angular radius.
    {
        std::vector<float> face = maps.readFace(0, 0);
        glm::dvec3 mean(0.0);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const float* p = &face[(size_t(y) * size + x) * 4];
                if (reddish({p[0], p[1], p[2]})) mean += glm::dvec3(envref::cubeTexelDirection(0, x, y, size));
            }
        ASSERT_GT(glm::length(mean), 0.0);
        double angle = std::acos(glm::dot(glm::normalize(mean), glm::normalize(glm::dvec3(offset))));
        EXPECT_LT(angle, 0.1) << "radians between the red texels and the neighbour";
    }
    EXPECT_EQ(maps.update(scene, {glossy}, capture), 0) << "nothing changed: no re-render";

    // Move the neighbour to -x: the map is re-rendered and the red moves to the -X face.
    scene.instances.back().transform = glm::translate(glm::mat4(1.0f), glm::vec3(-2.0f * offset.x, 0.0f, 0.0f)) *
                                       scene.instances.back().transform;
    EXPECT_EQ(maps.update(scene, {glossy}, capture), 1);
    EXPECT_EQ(redTexels(maps.readFace(0, 0)), 0);
    EXPECT_GT(redTexels(maps.readFace(0, 1)), 10);

    // Moving the glossy object itself moves the centroid the map is rendered from.
    scene.instances[glossy].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 0.5f)) *
                                        scene.instances[glossy].transform;
    EXPECT_EQ(maps.update(scene, {glossy}, capture), 1);
    EXPECT_NEAR(maps.centroid(0).z, centre.z + 0.5f, 1e-4f);
}

// Through the lighting pass: with ibl.object_maps = 1 the glossy sphere reflects a red neighbour on the side it
// stands, and the reflection moves when the neighbour moves; without object maps there is no red reflection.
TEST(RegularSamplingObjectEnvironment, ReflectionFollowsAMovedNeighbour) {
    auto context = createHeadlessContext(Backend::Egl);
    SphereAndNeighbour rig = sphereWithRedNeighbour(glm::vec3(1.6f, 0.0f, 0.3f), 0.6f);
    Scene& scene = rig.scene;
    const uint32_t glossy = rig.glossy;
    const uint32_t sphereMaterial = scene.instances[glossy].material;
    scene.materials[sphereMaterial].metallic = 1.0f;
    scene.materials[sphereMaterial].glinty = false;
    auto placeNeighbour = [&](float x) { return rig.place(glm::vec3(x, 0.0f, 0.3f), 0.6f); };
    // Sun from above and in front, so both neighbour positions are lit alike in the per-object maps.
    for (Light& light : scene.lights) {
        light.type = LightType::Directional;
        light.vector = glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f));
    }
    const Camera camera = scene.cameras.front();
    const int size = 96;

    // Number of distinctly red pixels of the glossy sphere, left and right of the image centre.
    auto measure = [&](bool objectMaps, glm::vec2& leftRight) {
        RenderSettings settings;
        settings.ibl = "regular";
        settings.apply("light.intensity=0");
        settings.apply("ibl.mx=0.05");
        settings.apply("ibl.my=0.05");
        settings.apply(std::string("ibl.object_maps=") + (objectMaps ? "1" : "0"));
        settings.apply("ibl.object_map_size=64");
        GpuScene gpuScene(scene);
        Renderer renderer(defaultShaderDir(), settings);
        renderer.renderView(scene, gpuScene, camera, size, size);
        std::vector<float> hdr = renderer.readHdr();
        static int image = 0;
        std::filesystem::path dir = std::filesystem::path(GLIMMER_TEST_OUTPUT_DIR) / "regular_sampling";
        std::filesystem::create_directories(dir);
        writeExr(dir / ("object_maps_" + std::to_string(image++) + ".exr"), hdr.data(), size, size);
        RenderSettings materialView = settings;
        materialView.debugView = findAov("material").viewId;
        renderer.setSettings(materialView);
        renderer.renderView(scene, gpuScene, camera, size, size);
        std::vector<float> ids = renderer.readHdr();
        glm::dvec2 sum(0.0), count(0.0);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                size_t i = (size_t(y) * size + x) * 4;
                if (ids[i + 3] <= 0.0f || std::lround(ids[i + 2]) != long(sphereMaterial)) continue;
                int side = x < size / 2 ? 0 : 1;
                sum[side] += reddish({hdr[i], hdr[i + 1], hdr[i + 2]}) ? 1.0 : 0.0;
                count[side] += 1.0;
            }
        ASSERT_GT(count.x, 50.0);
        ASSERT_GT(count.y, 50.0);
        leftRight = glm::vec2(sum);
    };
    glm::vec2 withMaps, without, moved;
    measure(true, withMaps);
    measure(false, without);
    scene.instances.back().transform = placeNeighbour(-1.6f);
    measure(true, moved);
    std::printf("red sphere pixels left/right: object maps %.0f %.0f, none %.0f %.0f, moved %.0f %.0f\n", withMaps.x,
                withMaps.y, without.x, without.y, moved.x, moved.y);
    EXPECT_GT(withMaps.y, 10.0f) << "the neighbour at +x is reflected on the right";
    EXPECT_EQ(withMaps.x, 0.0f);
    EXPECT_GT(moved.x, 10.0f) << "moved to -x, its reflection moves to the left";
    EXPECT_EQ(moved.y, 0.0f);
    EXPECT_EQ(without.x + without.y, 0.0f) << "the scene's environment has no neighbour in it";
}

}  // namespace
}  // namespace glimmer::ibl
