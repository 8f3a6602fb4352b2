// Area lights and light sizes in files: scene-file lights (rect, disk, sphere; a directional light's angular
// diameter, a point light's radius) and the glTF extension GLIMMER_lights_area (engine/scene/gltf_area_lights.h):
// every key lands where it should, placed by the node, and every bad value is a one-line error naming the file and
// the key. Also the GPU light record (render/gpu_scene.h gpuLight) and the GPU order of punctual and area lights.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "core/error.h"
#include "render/gpu_scene.h"
#include "scene/gltf_area_lights.h"
#include "scene/gltf_loader.h"
#include "scene/scene_file.h"
#include "support/process.h"

using namespace glimmer;

namespace {

// A one-triangle glTF with `top` inserted at the top level and `nodes` appended after the mesh's node (each extra
// node is a root of the scene).
std::string writeModel(const std::string& dir, const std::string& name, const std::string& top,
                       const std::string& nodes, int extraNodes) {
    float p[9] = {0, 0, 0, 2, 0, 0, 0, 0, 2};
    unsigned short idx[3] = {0, 2, 1};
    std::string bin(reinterpret_cast<char*>(p), sizeof p);
    bin.append(reinterpret_cast<char*>(idx), sizeof idx);
    bin.append(2, '\0');
    std::ofstream(dir + "/" + name + ".bin", std::ios::binary) << bin;
    std::string roots = "0";
    for (int i = 1; i <= extraNodes; ++i) roots += ", " + std::to_string(i);
    std::string path = dir + "/" + name + ".gltf";
    std::ofstream(path) << R"({"asset": {"version": "2.0"},)" << top << R"(
 "buffers": [{"uri": ")" << name << R"(.bin", "byteLength": )" << bin.size() << R"(}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [2, 0, 2]},
               {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
 "nodes": [{"mesh": 0})" << nodes << R"(], "scenes": [{"nodes": [)" << roots << R"(]}], "scene": 0})";
    return path;
}

std::string extension(const std::string& lights) {
    return R"( "extensionsUsed": ["GLIMMER_lights_area"], "extensions": {"GLIMMER_lights_area": {"lights": [)" + lights +
           "]}},";
}

template <class F>
std::string errorOf(F&& load) {
    try {
        load();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(AreaLightFiles, GltfExtensionPlacesRectDiskAndSphere) {
    std::string dir = test::makeTempDir("area_lights_gltf");
    std::string lights = extension(R"(
        {"type": "rect", "width": 1.2, "height": 0.4, "intensity": 60, "color": [1, 0.5, 0.25], "twoSided": true,
         "range": 12, "name": "panel"},
        {"type": "disk", "radius": 0.3, "intensity": 5},
        {"type": "sphere", "radius": 0.1, "intensity": 40})");
    // Node 1: the rect at (1, 3, 1) turned -90 degrees about x (shines down, -y; its width stays along +x);
    // node 2: the disk at the origin shining along -z; node 3: the sphere, whose node scale does not scale it.
    std::string nodes = R"(, {"translation": [1, 3, 1], "rotation": [-0.7071068, 0, 0, 0.7071068],
        "extensions": {"GLIMMER_lights_area": {"light": 0}}},
      {"extensions": {"GLIMMER_lights_area": {"light": 1}}},
      {"translation": [0, 2, 0], "scale": [5, 5, 5], "extensions": {"GLIMMER_lights_area": {"light": 2}}})";
    Scene s = loadGltfScene(writeModel(dir, "lit", lights, nodes, 3));
    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_FALSE(s.fallbackLights);
    const Light& r = s.lights[0];
    EXPECT_EQ(r.type, LightType::Rect);
    EXPECT_NEAR(r.vector.y, 3.0f, 1e-5f);
    EXPECT_NEAR(r.spotDirection.y, -1.0f, 1e-5f);
    EXPECT_NEAR(r.right.x, 1.0f, 1e-5f);
    EXPECT_FLOAT_EQ(r.width, 1.2f);
    EXPECT_FLOAT_EQ(r.height, 0.4f);
    EXPECT_FLOAT_EQ(r.intensity, 60.0f);
    EXPECT_FLOAT_EQ(r.color.y, 0.5f);
    EXPECT_TRUE(r.twoSided);
    EXPECT_FLOAT_EQ(r.range, 12.0f);
    EXPECT_EQ(s.lights[1].type, LightType::Disk);
    EXPECT_NEAR(s.lights[1].spotDirection.z, -1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(s.lights[1].radius, 0.3f);
    EXPECT_FALSE(s.lights[1].twoSided);
    EXPECT_EQ(s.lights[2].type, LightType::Sphere);
    EXPECT_FLOAT_EQ(s.lights[2].radius, 0.1f);
    EXPECT_NEAR(s.lights[2].vector.y, 2.0f, 1e-5f);
}

TEST(AreaLightFiles, BadExtensionValuesAreOneLineErrorsNamingFileAndKey) {
    std::string dir = test::makeTempDir("area_lights_bad");
    struct Case {
        const char* light;
        const char* key;
    };
    const Case cases[] = {
        {R"({"type": "rect", "width": -1, "height": 1})", "lights[0].width"},
        {R"({"type": "rect", "width": 1})", "lights[0].height"},
        {R"({"type": "rect", "width": 1, "height": "tall"})", "lights[0].height"},
        {R"({"type": "rect", "width": 1, "height": 1, "radius": 2})", "lights[0].radius"},
        {R"({"type": "disk"})", "lights[0].radius"},
        {R"({"type": "sphere", "radius": 0})", "lights[0].radius"},
        {R"({"type": "sphere", "radius": 1, "intensity": -3})", "lights[0].intensity"},
        {R"({"type": "sphere", "radius": 1, "color": [1, 2, 0]})", "lights[0].color[1]"},
        {R"({"type": "sphere", "radius": 1, "twoSided": true})", "lights[0].twoSided"},
        {R"({"type": "disk", "radius": 1, "twoSided": 1})", "lights[0].twoSided"},
        {R"({"type": "sphere", "radius": 1, "range": -1})", "lights[0].range"},
        {R"({"type": "sphere", "radius": 1, "brightness": 2})", "lights[0].brightness"},
        {R"({"type": "tube", "radius": 1})", "lights[0].type"},
        {R"({"radius": 1})", "lights[0].type"},
        {R"(7)", "lights[0]"},
    };
    std::string node = R"(, {"extensions": {"GLIMMER_lights_area": {"light": 0}}})";
    for (const Case& c : cases) {
        std::string path = writeModel(dir, "bad", extension(c.light), node, 1);
        std::string error = errorOf([&] { loadGltfScene(path); });
        EXPECT_NE(error.find(path), std::string::npos) << error;
        EXPECT_NE(error.find(std::string("GLIMMER_lights_area.") + c.key), std::string::npos) << c.light << ": " << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
    // A node's index that does not exist, a bad index, a singular node transform.
    std::string ok = extension(R"({"type": "sphere", "radius": 1})");
    for (const char* n : {R"(, {"extensions": {"GLIMMER_lights_area": {"light": 3}}})",
                          R"(, {"extensions": {"GLIMMER_lights_area": {"light": "first"}}})",
                          R"(, {"scale": [0, 0, 0], "extensions": {"GLIMMER_lights_area": {"light": 0}}})"}) {
        std::string path = writeModel(dir, "badnode", ok, n, 1);
        std::string error = errorOf([&] { loadGltfScene(path); });
        EXPECT_NE(error.find("GLIMMER_lights_area"), std::string::npos) << n << ": " << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
}

TEST(AreaLightFiles, SceneFileLightsAndSizes) {
    std::string dir = test::makeTempDir("area_lights_scene");
    std::string path = dir + "/lights.json";
    std::ofstream(path) << R"({"base": "plane90", "lights": [
        {"type": "directional", "direction": [0, 1, 0], "angularDiameterDegrees": 2.0},
        {"type": "directional", "direction": [0, 1, 1]},
        {"type": "point", "position": [0, 2, 0], "radius": 0.05},
        {"type": "rect", "position": [0, 3, 0], "direction": [0, -1, 0], "right": [0, 0, 1], "width": 2, "height": 0.5,
         "intensity": 30, "twoSided": true},
        {"type": "disk", "position": [1, 3, 0], "direction": [0, -1, 0], "radius": 0.4},
        {"type": "sphere", "position": [0, 1, 2], "radius": 0.2, "intensity": 8, "range": 10}]})";
    Scene s = loadSceneFile(path);
    ASSERT_EQ(s.lights.size(), 6u);
    EXPECT_NEAR(s.lights[0].angularDiameter, 2.0f * 3.14159265f / 180.0f, 1e-6f);
    EXPECT_NEAR(s.lights[1].angularDiameter, kSunAngularDiameter, 1e-6f);   // 0.53 degrees by default
    EXPECT_FLOAT_EQ(s.lights[2].radius, 0.05f);
    const Light& r = s.lights[3];
    EXPECT_EQ(r.type, LightType::Rect);
    EXPECT_NEAR(r.right.z, 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(r.width * r.height, r.area());
    EXPECT_FLOAT_EQ(r.radianceScale(), 30.0f / 1.0f);
    EXPECT_TRUE(r.twoSided);
    EXPECT_EQ(s.lights[4].type, LightType::Disk);
    // Without "right" a disk or rect facing down gets a horizontal width axis orthogonal to its normal.
    EXPECT_NEAR(glm::dot(s.lights[4].right, s.lights[4].spotDirection), 0.0f, 1e-6f);
    EXPECT_NEAR(s.lights[4].right.y, 0.0f, 1e-6f);
    EXPECT_EQ(s.lights[5].type, LightType::Sphere);
    EXPECT_NEAR(s.lights[5].radianceScale(), 8.0f / (3.14159265f * 0.04f), 1e-3f);
    EXPECT_FLOAT_EQ(s.lights[5].range, 10.0f);

    // The GPU order: punctual lights first (in scene order), then the area lights.
    std::vector<size_t> order = gpuLightOrder(s.lights);
    EXPECT_EQ(order, (std::vector<size_t>{0, 1, 2, 3, 4, 5}));
    std::vector<Light> mixed = {s.lights[3], s.lights[0], s.lights[5], s.lights[2]};
    EXPECT_EQ(gpuLightOrder(mixed), (std::vector<size_t>{1, 3, 0, 2}));

    // The records the shaders read: the sun's solid angle 2 pi (1 - cos(d / 2)), a rect's half-extents along its
    // width and height axes (front = cross(U, V) = its normal) and radiance, a sphere's radius.
    GpuLight sun = gpuLight(s.lights[1]);
    EXPECT_NEAR(sun.spotOffsetRange.z, 6.7201e-5f, 1e-8f);
    GpuLight rect = gpuLight(r);
    EXPECT_NEAR(glm::length(glm::vec3(rect.areaU)), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(glm::vec3(rect.areaV)), 0.25f, 1e-6f);
    glm::vec3 front = glm::normalize(glm::cross(glm::vec3(rect.areaU), glm::vec3(rect.areaV)));
    EXPECT_NEAR(front.y, -1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(rect.colorIntensity.w, 30.0f);
    EXPECT_FLOAT_EQ(rect.spotOffsetRange.w, 30.0f);
    EXPECT_FLOAT_EQ(rect.areaU.w, 1.0f);
    EXPECT_FLOAT_EQ(gpuLight(s.lights[5]).areaV.w, 0.2f);
}

TEST(AreaLightFiles, BadSceneFileLightsAreOneLineErrorsNamingTheKey) {
    std::string dir = test::makeTempDir("area_lights_scene_bad");
    struct Case {
        const char* light;
        const char* key;
    };
    const Case cases[] = {
        {R"({"type": "rect", "position": [0, 1, 0], "direction": [0, -1, 0], "width": 1})", "lights[0]"},
        {R"({"type": "rect", "position": [0, 1, 0], "direction": [0, -1, 0], "width": 0, "height": 1})", "lights[0].width"},
        {R"({"type": "rect", "position": [0, 1, 0], "direction": [0, -1, 0], "right": [0, 2, 0], "width": 1, "height": 1})",
         "lights[0].right"},
        {R"({"type": "rect", "position": [0, 1, 0], "width": 1, "height": 1})", "lights[0]"},
        {R"({"type": "disk", "position": [0, 1, 0], "direction": [0, -1, 0]})", "lights[0]"},
        {R"({"type": "sphere", "position": [0, 1, 0], "radius": -1})", "lights[0].radius"},
        {R"({"type": "sphere", "position": [0, 1, 0], "radius": 1, "width": 2})", "lights[0].width"},
        {R"({"type": "point", "position": [0, 1, 0], "radius": -0.1})", "lights[0].radius"},
        {R"({"type": "point", "position": [0, 1, 0], "angularDiameterDegrees": 1})", "lights[0].angularDiameterDegrees"},
        {R"({"type": "directional", "direction": [0, 1, 0], "angularDiameterDegrees": 120})",
         "lights[0].angularDiameterDegrees"},
        {R"({"type": "tube", "position": [0, 1, 0]})", "lights[0].type"},
    };
    for (const Case& c : cases) {
        std::string path = dir + "/bad.json";
        std::ofstream(path) << R"({"base": "plane90", "lights": [)" << c.light << "]}";
        std::string error = errorOf([&] { loadSceneFile(path); });
        EXPECT_NE(error.find(path), std::string::npos) << error;
        EXPECT_NE(error.find(c.key), std::string::npos) << c.light << ": " << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
}
