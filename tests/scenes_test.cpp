// Scenes: glTF loading (checked against counts read straight from each file's JSON), KHR_texture_transform
// through the real G-buffer pass, tangent frames, the scene-file format, and the generated atrium (counts,
// metric UVs, renders of every camera, footprint anisotropy at the grazing camera).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <tuple>

#include "core/error.h"
#include "core/files.h"
#include "offscreen/offscreen.h"
#include "render/aov.h"
#include "scene/atrium.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/scene_file.h"
#include "scene/scene_loader.h"
#include "support/golden.h"
#include "support/measure.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(ScenesGltf, GlContext);
GLIMMER_SUITE_NEEDS(ScenesAtrium, GlContext);

namespace fs = std::filesystem;
using glimmer::Scene;

namespace {

fs::path assetsDir() {
    if (const char* env = std::getenv("GLIMMER_ASSETS_DIR"); env && *env) return env;
    fs::path beside = fs::path(GLIMMER_SOURCE_DIR) / ".." / "shared" / "assets";
    if (fs::is_directory(beside)) return beside;
    return "/work/shared/assets";
}

std::vector<fs::path> gltfModels() {
    std::vector<fs::path> files;
    fs::path models = assetsDir() / "models";
    if (!fs::is_directory(models)) return files;
    for (const auto& entry : fs::recursive_directory_iterator(models))
        if (entry.is_regular_file() && (entry.path().extension() == ".gltf" || entry.path().extension() == ".glb"))
            files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

// A required extension the loader refuses by design (compressed geometry), read from the JSON, or "".
std::string refusedRequiredExtension(const fs::path& file) {
    if (file.extension() != ".gltf") return "";
    std::ifstream in(file);
    nlohmann::json g = nlohmann::json::parse(in, nullptr, false);
    if (!g.is_object() || !g.contains("extensionsRequired")) return "";
    for (const auto& ext : g["extensionsRequired"]) {
        const std::string name = ext.get<std::string>();
        if (name == "KHR_draco_mesh_compression" || name == "EXT_meshopt_compression") return name;
    }
    return "";
}

// Models that must load: every shared model but those refused by name (checked in RefusedModelsNameTheExtension).
std::vector<fs::path> loadableGltfModels() {
    std::vector<fs::path> files;
    for (const fs::path& f : gltfModels())
        if (refusedRequiredExtension(f).empty()) files.push_back(f);
    return files;
}

fs::path testData(const std::string& name) { return fs::path(GLIMMER_TEST_DIR) / "data" / name; }

// What a glTF file should load as, computed from its JSON alone (no tinygltf): triangles drawn by the default
// scene's node tree, instances (node x triangle primitive), distinct primitive geometries, materials.
struct ExpectedCounts {
    size_t triangles = 0, instances = 0, meshes = 0, materials = 0;
};

ExpectedCounts expectedFromJson(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (file.extension() == ".glb") {
        // GLB: 12-byte header, then the JSON chunk (uint32 length, "JSON", text).
        uint32_t length = 0;
        if (bytes.size() >= 20) std::memcpy(&length, bytes.data() + 12, 4);
        bytes = bytes.size() >= 20 + size_t(length) ? bytes.substr(20, length) : std::string();
    }
    nlohmann::json g = nlohmann::json::parse(bytes);
    ExpectedCounts e;
    auto isTriangles = [](const nlohmann::json& p) { return !p.contains("mode") || p["mode"].get<int>() == 4; };
    auto attribute = [](const nlohmann::json& p, const char* name) {
        return p["attributes"].contains(name) ? p["attributes"][name].get<int>() : -1;
    };
    std::set<std::tuple<int, int, int, int, int, int>> geometries;
    bool needsDefaultMaterial = false;
    for (const auto& mesh : g["meshes"])
        for (const auto& p : mesh["primitives"]) {
            if (!isTriangles(p)) continue;
            geometries.insert({attribute(p, "POSITION"), attribute(p, "NORMAL"), attribute(p, "TANGENT"),
                               attribute(p, "TEXCOORD_0"), attribute(p, "COLOR_0"), p.value("indices", -1)});
            needsDefaultMaterial |= !p.contains("material");
        }
    e.meshes = geometries.size();
    e.materials = g.value("materials", nlohmann::json::array()).size() + (needsDefaultMaterial ? 1 : 0);
    std::function<void(int)> visit = [&](int node) {
        const auto& n = g["nodes"][size_t(node)];
        if (n.contains("mesh"))
            for (const auto& p : g["meshes"][n["mesh"].get<size_t>()]["primitives"]) {
                if (!isTriangles(p)) continue;
                size_t count = p.contains("indices") ? g["accessors"][p["indices"].get<size_t>()]["count"].get<size_t>()
                                                     : g["accessors"][size_t(attribute(p, "POSITION"))]["count"].get<size_t>();
                e.triangles += count / 3;
                ++e.instances;
            }
        for (const auto& child : n.value("children", nlohmann::json::array())) visit(child.get<int>());
    };
    int sceneIndex = g.value("scene", 0);
    for (const auto& root : g["scenes"][size_t(sceneIndex)]["nodes"]) visit(root.get<int>());
    return e;
}

// Frames must be finite, unit-length and orthogonal; handedness is +-1.
void expectValidFrames(const glimmer::MeshData& mesh, const std::string& what) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << what;
    ASSERT_EQ(mesh.tangents.size(), mesh.positions.size()) << what;
    ASSERT_EQ(mesh.uvs.size(), mesh.positions.size()) << what;
    size_t bad = 0;
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        glm::vec3 n = mesh.normals[v], t = glm::vec3(mesh.tangents[v]);
        float w = mesh.tangents[v].w;
        bool ok = std::abs(glm::length(n) - 1.0f) < 1e-3f && std::abs(glm::length(t) - 1.0f) < 2e-2f &&
                  std::abs(glm::dot(n, t)) < 2e-2f && std::abs(std::abs(w) - 1.0f) < 1e-6f &&
                  std::isfinite(mesh.uvs[v].x) && std::isfinite(mesh.uvs[v].y);
        bad += !ok;
    }
    // Authored tangents (glTF TANGENT) can be slightly off; allow a tiny fraction, generated ones must all pass.
    EXPECT_LE(bad, mesh.positions.size() / 200) << what << ": " << bad << " vertices with an invalid frame";
}

struct ImageStats {
    double coveredFraction = 0.0;  // pixels that differ from the sky colour
    double luminanceStdDev = 0.0;  // over covered pixels
    size_t nonFinite = 0;
};

ImageStats imageStats(const glimmer::RenderResult& r, glm::vec3 sky) {
    ImageStats s;
    double sum = 0.0, sum2 = 0.0;
    size_t covered = 0;
    for (size_t i = 0; i + 3 < r.hdr.size(); i += 4) {
        glm::vec3 c(r.hdr[i], r.hdr[i + 1], r.hdr[i + 2]);
        if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) { ++s.nonFinite; continue; }
        if (glm::length(c - sky) < 1e-3f) continue;
        double y = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
        sum += y;
        sum2 += y * y;
        ++covered;
    }
    s.coveredFraction = double(covered) / double(r.width * r.height);
    if (covered > 1) s.luminanceStdDev = std::sqrt(std::max(0.0, sum2 / covered - (sum / covered) * (sum / covered)));
    return s;
}

glimmer::RenderRequest request(const std::string& scene, const std::string& camera, const std::string& aov = "final") {
    glimmer::RenderRequest r;
    r.scene = scene;
    r.camera = camera;
    r.width = r.height = 256;
    r.settings.debugView = glimmer::findAov(aov).viewId;
    return r;
}

// Error text must be one line and name the file.
void expectOneLineErrorNaming(const std::function<void()>& load, const std::string& fileName) {
    try {
        load();
        ADD_FAILURE() << "no error for " << fileName;
    } catch (const glimmer::Error& e) {
        std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_NE(message.find(fileName), std::string::npos) << message;
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// glTF models in the shared assets

TEST(ScenesGltf, RefusedModelsNameTheExtension) {
    int refused = 0;
    for (const fs::path& file : gltfModels()) {
        const std::string ext = refusedRequiredExtension(file);
        if (ext.empty()) continue;
        ++refused;
        try {
            glimmer::loadScene(file.string());
            ADD_FAILURE() << file << " requires " << ext << " but loaded";
        } catch (const glimmer::Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("requires extension " + ext), std::string::npos) << what;
            EXPECT_NE(what.find(file.string()), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
    if (refused == 0) GTEST_SKIP() << "no shared model requires a refused extension";
}

TEST(ScenesGltf, EveryModelLoadsWithTheCountsOfItsJson) {
    std::vector<fs::path> models = loadableGltfModels();
    if (models.empty()) GTEST_SKIP() << "no glTF models under " << assetsDir();
    for (const fs::path& file : models) {
        SCOPED_TRACE(file.string());
        ExpectedCounts expected = expectedFromJson(file);
        Scene scene = glimmer::loadScene(file.string());
        EXPECT_EQ(scene.triangleCount(), expected.triangles);
        EXPECT_EQ(scene.instances.size(), expected.instances);
        EXPECT_EQ(scene.meshes.size(), expected.meshes);
        EXPECT_EQ(scene.materials.size(), expected.materials);
        ASSERT_FALSE(scene.cameras.empty());
        for (const glimmer::MeshData& mesh : scene.meshes) expectValidFrames(mesh, mesh.name);
        for (const glimmer::TextureData& t : scene.textures)
            EXPECT_EQ(t.rgba.size(), size_t(t.width) * size_t(t.height) * 4) << t.name;
    }
}

// One session per model (about 1.3 s each). CI: every model except the Khronos test models that
// khronos_conformance_test.cpp renders and checks in detail (AlphaBlendModeTest, EmissiveStrengthTest,
// NegativeScaleTest, NormalTangentTest, TextureSettingsTest, TextureTransformTest, VertexColorTest);
// GLIMMER_MEASURE=1 renders those here too.
TEST(ScenesGltf, EveryModelRendersSomethingVaried) {
    std::vector<fs::path> models = loadableGltfModels();
    if (models.empty()) GTEST_SKIP() << "no glTF models under " << assetsDir();
    if (!glimmer::test::fullMeasurement()) {
        const std::set<std::string> renderedByConformance = {"AlphaBlendModeTest", "EmissiveStrengthTest",
                                                             "NegativeScaleTest", "NormalTangentTest",
                                                             "TextureSettingsTest", "TextureTransformTest",
                                                             "VertexColorTest"};
        std::erase_if(models, [&](const fs::path& f) { return renderedByConformance.count(f.stem().string()) > 0; });
    }
    for (const fs::path& file : models) {
        SCOPED_TRACE(file.string());
        glimmer::RenderRequest r = request(file.string(), "");
        glimmer::OffscreenSession session(r);
        glm::vec3 sky = session.scene().skyColor;
        glimmer::RenderResult result = session.render(r);
        ImageStats s = imageStats(result, sky);
        EXPECT_EQ(s.nonFinite, 0u);
        EXPECT_GT(s.coveredFraction, 0.03) << "the framing camera should show the model";
        EXPECT_GT(s.luminanceStdDev, 0.01) << "a lit model is not a flat colour";
    }
}

TEST(ScenesGltf, ModelTexturesAreDecodedAndTransformsRead) {
    fs::path car = assetsDir() / "models" / "ClearCoatCarPaint" / "glTF" / "ClearCoatCarPaint.gltf";
    if (!fs::exists(car)) GTEST_SKIP() << car << " missing";
    // Requires KHR_materials_clearcoat (factor 1, roughness 0, no coat textures) and KHR_texture_transform
    // (scale 3 on the normal map), and normalTexture.scale = 0.2 (baked into the texture).
    Scene scene = glimmer::loadGltfScene(car);
    ASSERT_EQ(scene.materials.size(), 1u);
    const glimmer::Material& m = scene.materials[0];
    EXPECT_EQ(m.clearcoat, 1.0f);
    EXPECT_EQ(m.clearcoatRoughness, 0.0f);
    EXPECT_EQ(m.clearcoatNormalTexture, -1);
    ASSERT_GE(m.normalTexture, 0);
    glm::vec3 uv = m.uvTransform * glm::vec3(0.1f, 0.2f, 1.0f);
    EXPECT_NEAR(uv.x, 0.3f, 1e-6f);
    EXPECT_NEAR(uv.y, 0.6f, 1e-6f);
    // With scale 0.2 every decoded normal must be within asin(0.2 * |xy|max) of +z: z >= ~0.98 in [-1,1].
    const glimmer::TextureData& normal = scene.textures[size_t(m.normalTexture)];
    float minZ = 1.0f;
    for (size_t i = 0; i + 3 < normal.rgba.size(); i += 4) minZ = std::min(minZ, normal.rgba[i + 2] / 127.5f - 1.0f);
    EXPECT_GT(minZ, 0.95f);
}

// ---------------------------------------------------------------------------------------------------------------
// Hand-written glTF files (tests/data)

TEST(ScenesGltf, CorruptFileGivesOneLineErrorNamingIt) {
    expectOneLineErrorNaming([] { glimmer::loadScene(testData("corrupt.gltf").string()); }, "corrupt.gltf");
}

TEST(ScenesGltf, MissingOrShortBufferGivesOneLineErrorNamingTheFile) {
    expectOneLineErrorNaming([] { glimmer::loadScene(testData("bad_buffer.gltf").string()); }, "bad_buffer.gltf");
    expectOneLineErrorNaming([] { glimmer::loadScene(testData("short_buffer.gltf").string()); }, "short_buffer.gltf");
    expectOneLineErrorNaming([] { glimmer::loadScene(testData("no_such_file.gltf").string()); }, "no_such_file.gltf");
}

// Extensions the engine does not implement are ignored with a warning, even when marked required, as long as
// the model still renders meaningfully (here: a required material extension and an image tinygltf cannot
// decode, as with KHR_texture_basisu); geometry compression cannot be ignored and is refused by name.
TEST(ScenesGltf, UnsupportedExtensionsAreIgnoredOrRefusedByName) {
    Scene scene = glimmer::loadGltfScene(testData("undecodable_image.gltf"));
    EXPECT_EQ(scene.triangleCount(), 4u);
    ASSERT_EQ(scene.materials.size(), 3u);
    for (const glimmer::Material& m : scene.materials) EXPECT_EQ(m.baseColorTexture, -1) << m.name;
    try {
        glimmer::loadGltfScene(testData("requires_draco.gltf"));
        ADD_FAILURE() << "a required KHR_draco_mesh_compression must be refused";
    } catch (const glimmer::Error& e) {
        std::string message = e.what();
        EXPECT_NE(message.find("requires_draco.gltf"), std::string::npos) << message;
        EXPECT_NE(message.find("KHR_draco_mesh_compression"), std::string::npos) << message;
    }
}

TEST(ScenesGltf, TextureTransformMatrixFollowsTheExtension) {
    Scene scene = glimmer::loadGltfScene(testData("texture_transform.gltf"));
    ASSERT_EQ(scene.materials.size(), 3u);
    // "plain": identity. "transformed": offset (0.5, 0), scale (2, 1): uv' = (2u + 0.5, v).
    // "rotated": rotation pi/2 with the extension's matrix [cos sin; -sin cos]: uv' = (v, -u).
    glm::vec3 p = scene.materials[0].uvTransform * glm::vec3(0.3f, 0.1f, 1.0f);
    glm::vec3 t = scene.materials[1].uvTransform * glm::vec3(0.3f, 0.1f, 1.0f);
    glm::vec3 r = scene.materials[2].uvTransform * glm::vec3(0.3f, 0.1f, 1.0f);
    EXPECT_NEAR(p.x, 0.3f, 1e-6f); EXPECT_NEAR(p.y, 0.1f, 1e-6f);
    EXPECT_NEAR(t.x, 1.1f, 1e-6f); EXPECT_NEAR(t.y, 0.1f, 1e-6f);
    EXPECT_NEAR(r.x, 0.1f, 1e-6f); EXPECT_NEAR(r.y, -0.3f, 1e-6f);
    ASSERT_EQ(scene.cameras.size(), 2u);
    EXPECT_EQ(scene.cameras[1].name, "front");
}

// The transform must change the UVs the G-buffer pass samples with: render the albedo of two quads using the
// same 8x8 texture (left half red, right half green), one plain and one with offset 0.5, scale 2 along u,
// and compare the colour at the centres of the quads' four vertical quarters with the CPU prediction.
TEST(ScenesGltf, TextureTransformChangesTheSampledTexels) {
    glimmer::RenderRequest r = request(testData("texture_transform.gltf").string(), "front", "albedo");
    glimmer::RenderResult result = glimmer::renderOffscreen(r);
    const float distance = 6.0f, tanHalf = std::tan(glm::radians(45.0f) * 0.5f);
    auto pixelOf = [&](float x, float y) {
        int px = int((x / (distance * tanHalf) * 0.5f + 0.5f) * r.width);
        int py = int((y / (distance * tanHalf) * 0.5f + 0.5f) * r.height);
        return glm::vec3(result.hdr[(size_t(py) * r.width + px) * 4], result.hdr[(size_t(py) * r.width + px) * 4 + 1],
                         result.hdr[(size_t(py) * r.width + px) * 4 + 2]);
    };
    auto textureRedAt = [](float u) { return std::fmod(std::fmod(u, 1.0f) + 1.0f, 1.0f) < 0.5f; };
    for (int quad = 0; quad < 2; ++quad) {
        float x0 = quad == 0 ? -2.1f : 0.1f;
        for (int quarter = 0; quarter < 4; ++quarter) {
            float u = (quarter + 0.5f) / 4.0f;
            float transformedU = quad == 0 ? u : 2.0f * u + 0.5f;
            glm::vec3 c = pixelOf(x0 + 2.0f * u, 0.3f);
            bool red = textureRedAt(transformedU);
            SCOPED_TRACE("quad " + std::to_string(quad) + " quarter " + std::to_string(quarter));
            EXPECT_NEAR(c.x, red ? 1.0f : 0.0f, 0.02f);
            EXPECT_NEAR(c.y, red ? 0.0f : 1.0f, 0.02f);
        }
    }
}

// texture_anisotropy reaches the material textures: at the default (16) the albedo equals a render that sets 16,
// and at 1 (trilinear: the mip level of the footprint's major axis) the grazing floor is blurrier, so the summed
// difference between neighbouring albedo pixels there is smaller. Probes, AO and shadows off: albedo only.
TEST(ScenesAtrium, TextureAnisotropyCapBlursTheGrazingFloor) {
    auto albedo = [](const char* anisotropy) {
        glimmer::RenderRequest r = request("atrium", "grazing", "albedo");
        r.width = 256;
        r.height = 144;
        r.environment = "none";
        for (const char* s : {"probes.enabled=0", "ao.enabled=0", "shadow.enabled=0"}) r.settings.apply(s);
        if (anisotropy) r.settings.apply(std::string("texture_anisotropy=") + anisotropy);
        return glimmer::renderOffscreen(r);
    };
    glimmer::RenderResult byDefault = albedo(nullptr), sixteen = albedo("16"), trilinear = albedo("1");
    EXPECT_EQ(byDefault.hdr, sixteen.hdr);
    auto contrast = [](const glimmer::RenderResult& result) {
        double sum = 0.0;
        // Rows 40-55 % down: the floor some metres away, where the footprint is most anisotropic.
        for (int y = result.height * 40 / 100; y < result.height * 55 / 100; ++y)
            for (int x = 0; x + 1 < result.width; ++x)
                for (int c = 0; c < 3; ++c) {
                    const size_t i = (size_t(y) * result.width + x) * 4 + c;
                    sum += std::abs(result.hdr[i + 4] - result.hdr[i]) +
                           std::abs(result.hdr[i + size_t(result.width) * 4] - result.hdr[i]);
                }
        return sum;
    };
    const double sharp = contrast(sixteen), blurred = contrast(trilinear);
    std::printf("[ anisotropy ] floor neighbour contrast: 16x %.1f, trilinear %.1f\n", sharp, blurred);
    EXPECT_LT(blurred, 0.95 * sharp);
}

// ---------------------------------------------------------------------------------------------------------------
// Tangent generation

// A planar quad whose UV axes are rotated and mirrored relative to the geometry: the generated tangent must be
// the unit dP/du, orthogonal to the normal, and the sign w must make w * cross(n, t) point along dP/dv (UvUp, the
// built-in scenes) or along -dP/dv (ImageUp, glTF: v runs down the image, normal maps are +Y up).
TEST(ScenesTangents, GeneratedFramesFollowUvDirections) {
    using glimmer::BitangentConvention;
    for (BitangentConvention convention : {BitangentConvention::UvUp, BitangentConvention::ImageUp})
        for (bool mirrored : {false, true})
            for (float angle : {0.0f, 0.7f, 2.5f}) {
                glimmer::MeshData mesh;
                glm::vec3 n = glm::normalize(glm::vec3(0.2f, 1.0f, -0.3f));
                glm::vec3 a = glm::normalize(glm::cross(n, glm::vec3(1, 0, 0))), b = glm::cross(n, a);
                // dP/du and dP/dv for the UV mapping uv = R(angle) * (x, +-y) on the plane's (a, b) coordinates.
                glm::vec3 dPdu = std::cos(angle) * a + std::sin(angle) * b;
                glm::vec3 dPdv = (mirrored ? -1.0f : 1.0f) * (-std::sin(angle) * a + std::cos(angle) * b);
                for (glm::vec2 uv : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
                    mesh.positions.push_back(uv.x * dPdu + uv.y * dPdv);
                    mesh.normals.push_back(n);
                    mesh.uvs.push_back(uv);
                }
                mesh.indices = {0, 1, 2, 0, 2, 3};
                glimmer::generateTangents(mesh, convention);
                const bool imageUp = convention == BitangentConvention::ImageUp;
                const glm::vec3 wanted = imageUp ? -dPdv : dPdv;
                for (const glm::vec4& t : mesh.tangents) {
                    EXPECT_NEAR(glm::dot(glm::vec3(t), dPdu), 1.0f, 1e-5f);
                    EXPECT_NEAR(glm::dot(glm::vec3(t), n), 0.0f, 1e-5f);
                    EXPECT_GT(glm::dot(t.w * glm::cross(n, glm::vec3(t)), wanted), 0.99f);
                    EXPECT_EQ(t.w, (mirrored != imageUp) ? -1.0f : 1.0f) << "(a, b, n) is right-handed; mirroring flips w";
                }
            }
}

// On a curved surface with an analytic parametrisation (the UV sphere: u = r phi, v = r theta) the generated
// tangents must match dP/du normalised away from the poles.
TEST(ScenesTangents, GeneratedTangentsMatchAnalyticSphereTangents) {
    glimmer::MeshData sphere = glimmer::makeUvSphere(1.0f, 64, 32);
    std::vector<glm::vec4> analytic = sphere.tangents;
    sphere.tangents.clear();
    glimmer::generateTangents(sphere, glimmer::BitangentConvention::UvUp);   // the built-in scenes' convention
    expectValidFrames(sphere, "sphere");
    for (size_t v = 0; v < sphere.positions.size(); ++v) {
        if (std::abs(sphere.normals[v].y) > 0.95f) continue;  // pole rows: dP/du vanishes
        EXPECT_GT(glm::dot(glm::vec3(sphere.tangents[v]), glm::vec3(analytic[v])), 0.995f) << v;
        EXPECT_EQ(sphere.tangents[v].w, analytic[v].w) << v;
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Scene files

namespace {
fs::path writeTemp(const std::string& name, const std::string& text) {
    fs::path dir = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "scenes";
    fs::create_directories(dir);
    fs::path file = dir / name;
    std::ofstream(file) << text;
    return file;
}
}  // namespace

TEST(ScenesFile, BaseOverridesAndAdditions) {
    fs::path file = writeTemp("file_test.json", R"({
      "base": "plane90",
      "sky": [0.1, 0.2, 0.3],
      "environment": "maps/sky.hdr",
      "meshes": [{"name": "ball", "generator": "sphere", "radius": 0.5, "segments": 16, "rings": 8},
                 {"name": "block", "generator": "box", "size": [1, 2, 3]}],
      "models": [{"gltf": ")" + testData("texture_transform.gltf").string() + R"(", "translation": [0, 5, 0]}],
      "materials": [{"name": "plane", "alpha": 0.05, "glintDensityScale": 3},
                    {"name": "red", "baseColor": [1, 0, 0], "roughness": 0.5, "glinty": false, "uvScale": 0.5}],
      "instances": [{"mesh": "ball", "material": "red", "translation": [0, 1, 0]},
                    {"mesh": "block", "material": "plane", "rotationDegrees": [0, 90, 0], "scale": 2}],
      "lights": [{"type": "point", "position": [0, 3, 0], "intensity": 5}],
      "cameras": [{"name": "a", "position": [0, 2, 5], "target": [0, 0, 0]},
                  {"name": "b", "position": [5, 2, 0], "target": [0, 0, 0], "fov": 30}],
      "walkthrough": ["b", "a"]
    })");
    Scene base = glimmer::makeBuiltinScene("plane90");
    Scene s = glimmer::loadScene(file.string());
    EXPECT_EQ(s.name, "file_test");
    EXPECT_EQ(s.skyColor, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(fs::path(s.environment), file.parent_path() / "maps" / "sky.hdr") << "relative to the scene file";
    // plane90 (1 mesh, 1 material) + 2 generated meshes + the glTF (2 meshes, 3 materials, 2 instances).
    ASSERT_EQ(s.meshes.size(), base.meshes.size() + 2 + 2);
    ASSERT_EQ(s.materials.size(), base.materials.size() + 3 + 1);
    ASSERT_EQ(s.instances.size(), base.instances.size() + 2 + 2);
    EXPECT_EQ(s.materials[0].name, "plane");
    EXPECT_FLOAT_EQ(s.materials[0].alpha, 0.05f);
    EXPECT_FLOAT_EQ(s.materials[0].glintDensityScale, 3.0f);
    EXPECT_EQ(s.materials[0].glinty, base.materials[0].glinty) << "fields the file leaves out are kept";
    const glimmer::Material& red = s.materials.back();
    EXPECT_FLOAT_EQ(red.alpha, 0.25f);
    EXPECT_FLOAT_EQ((red.uvTransform * glm::vec3(1, 1, 1)).x, 0.5f);
    EXPECT_EQ(s.triangleCount(), base.triangleCount() + 16 * 8 * 2 + 12 + 4);
    // The glTF instances keep their own transforms under the model's.
    EXPECT_FLOAT_EQ(s.instances[base.instances.size()].transform[3][1], 5.0f);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].type, glimmer::LightType::Point);
    ASSERT_EQ(s.cameras.size(), 2u);
    EXPECT_EQ(s.camera("b").verticalFovDegrees, 30.0f);
    EXPECT_EQ(s.walkthrough, (std::vector<std::string>{"b", "a"}));
}

TEST(ScenesFile, MistakesGiveOneLineErrorsNamingFileAndKey) {
    struct Case { const char* name; const char* text; const char* mentions; };
    const Case cases[] = {
        {"bad_json.json", R"({"base": "plane90",)", "invalid JSON"},
        {"unknown_key.json", R"({"base": "plane90", "camras": []})", "camras"},
        {"bad_base.json", R"({"base": "nowhere"})", "nowhere"},
        {"bad_material.json", R"({"base": "plane90", "materials": [{"name": "plane", "alpha": "rough"}]})", "materials[0].alpha"},
        {"bad_range.json", R"({"base": "plane90", "materials": [{"name": "plane", "metallic": 2}]})", "materials[0].metallic"},
        {"bad_instance.json", R"({"base": "plane90", "instances": [{"mesh": "nope", "material": "plane"}]})", "nope"},
        {"bad_walk.json", R"({"base": "plane90", "walkthrough": ["top", "ghost"]})", "ghost"},
        {"bad_camera.json", R"({"base": "plane90", "cameras": [{"name": "c", "position": [0, 1, 0], "target": [0, 1, 0]}]})", "cameras[0]"},
        {"bad_light.json", R"({"base": "plane90", "lights": [{"type": "spot", "position": [0, 1, 0]}]})", "lights[0]: a spot light needs"},
        {"bad_model.json", R"({"base": "plane90", "models": [{"gltf": "missing.gltf"}]})", "missing.gltf"},
        {"empty.json", R"({"sky": [0, 0, 0]})", "nothing to render"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        fs::path file = writeTemp(c.name, c.text);
        try {
            glimmer::loadScene(file.string());
            ADD_FAILURE() << "no error";
        } catch (const glimmer::Error& e) {
            std::string message = e.what();
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            EXPECT_NE(message.find(c.name), std::string::npos) << message;
            EXPECT_NE(message.find(c.mentions), std::string::npos) << message;
        }
    }
}

TEST(ScenesFile, NamesResolveToContentFilesThenBuiltins) {
    EXPECT_EQ(glimmer::loadScene("plane90").name, "plane90") << "generated scenes keep working";
    std::vector<std::string> content = glimmer::contentSceneNames();
    EXPECT_NE(std::find(content.begin(), content.end(), "atrium"), content.end());
    // "atrium" is content/atrium.json on top of the generator: its geometry plus the file's one mesh (the arcade's rect
    // light panel, a box of 12 triangles with its own material), the file's cameras and lights.
    Scene generated = glimmer::makeBuiltinScene("atrium"), described = glimmer::loadScene("atrium");
    EXPECT_EQ(generated.triangleCount() + 12, described.triangleCount());
    EXPECT_EQ(generated.materials.size() + 1, described.materials.size());
    EXPECT_EQ(generated.cameras.size(), 1u);
    EXPECT_GT(described.cameras.size(), generated.cameras.size());
    EXPECT_THROW(glimmer::loadScene("no_such_scene"), glimmer::UsageError);
    EXPECT_THROW(glimmer::loadScene("scene.obj"), glimmer::UsageError);
    // content/atrium.path.json is a camera path, not a scene: the list of known scenes (and the error that shows
    // it) leaves it out (issue 39, 13).
    ASSERT_TRUE(std::filesystem::exists(glimmer::defaultContentDir() / "atrium.path.json"));
    EXPECT_EQ(std::find(content.begin(), content.end(), "atrium.path"), content.end());
    try {
        glimmer::loadScene("no_such_scene");
    } catch (const glimmer::UsageError& e) {
        std::string message = e.what();
        EXPECT_EQ(message.find("atrium.path"), std::string::npos) << message;
        EXPECT_NE(message.find("area_lights"), std::string::npos) << message;
    }
}

// ---------------------------------------------------------------------------------------------------------------
// The atrium

namespace {
const Scene& atriumScene() {
    static const Scene scene = glimmer::loadScene("atrium");
    return scene;
}
const glimmer::MeshData& meshNamed(const Scene& s, const std::string& name) {
    for (const glimmer::MeshData& m : s.meshes)
        if (m.name == name) return m;
    throw std::runtime_error("no mesh " + name);
}
}  // namespace

TEST(ScenesAtrium, CountsMatchTheLayout) {
    const Scene& s = atriumScene();
    using namespace glimmer::atrium;
    // Triangle counts of the regular pieces, from their documented tessellations:
    // floor: 1 m cells over 31 m x 16 m plus one quad per gallery floor; snow: 4 patches of a 64-gon fan and
    // 5 rings of 128 triangles; drapes: 64 x 28 cells each, 8 drapes alternating red, blue, green;
    // relief 96 x 96 cells; vase 40 x 48; egg 48 x 64; sphere 48 x 96.
    const int floorCells = int(2 * (kCourtHalfX + kAisle)) * int(2 * (kCourtHalfZ + kAisle));
    EXPECT_EQ(meshNamed(s, "floor").triangleCount(), size_t(2 * floorCells + 4 * 2));
    EXPECT_EQ(meshNamed(s, "snow").triangleCount(), size_t(4 * (64 + 5 * 128)));
    EXPECT_EQ(meshNamed(s, "drapes_red").triangleCount(), size_t(3 * 64 * 28 * 2));
    EXPECT_EQ(meshNamed(s, "drapes_blue").triangleCount(), size_t(3 * 64 * 28 * 2));
    EXPECT_EQ(meshNamed(s, "drapes_green").triangleCount(), size_t(2 * 64 * 28 * 2));
    EXPECT_EQ(meshNamed(s, "relief").triangleCount(), size_t(96 * 96 * 2));
    EXPECT_EQ(meshNamed(s, "vase").triangleCount(), size_t(40 * 48 * 2));
    EXPECT_EQ(meshNamed(s, "egg").triangleCount(), size_t(48 * 64 * 2));
    EXPECT_EQ(meshNamed(s, "sphere").triangleCount(), size_t(48 * 96 * 2));
    // Columns: each storey has kColumnsPerStorey shafts of 20 segments (40 triangles), plus plinth and capital
    // boxes; arches: 24 soffit segments per bay. Check the stonework holds at least the shafts and soffits.
    const size_t bays = size_t(2 * (kLongBays + kShortBays)), storeys = 2;
    EXPECT_GE(meshNamed(s, "stonework").triangleCount(), storeys * (kColumnsPerStorey * 40 + bays * 24 * 2));
    EXPECT_EQ(s.meshes.size(), 12u);
    // Meshes: floor, walls, stonework, snow, 3 drapes, relief, vase, egg, sphere, and content/atrium.json's rect
    // light panel over the arcade. Instances: the first 8 once, 4 vases, 2 eggs, 1 sphere, the panel.
    EXPECT_EQ(s.instances.size(), 16u);
    EXPECT_GT(s.triangleCount(), 50000u);
    EXPECT_LT(s.triangleCount(), 300000u) << "budget: llvmpipe renders 512x512 well under a second";

    std::set<std::string> glinty, matte;
    for (const glimmer::Material& m : s.materials) (m.glinty ? glinty : matte).insert(m.name);
    EXPECT_EQ(glinty, (std::set<std::string>{"snow", "car_paint_red", "car_paint_blue", "drape_red", "drape_blue", "drape_green"}));
    EXPECT_EQ(matte, (std::set<std::string>{"ashlar", "stone", "floor_tiles", "bronze", "terracotta", "light_panel"}));
    EXPECT_EQ(s.textures.size(), 3u);

    // A sun, the lanterns as sphere lights and the arcade's rect light; at least five named cameras, all on the
    // walkthrough path.
    ASSERT_FALSE(s.lights.empty());
    EXPECT_EQ(s.lights[0].type, glimmer::LightType::Directional);
    EXPECT_GE(std::count_if(s.lights.begin(), s.lights.end(), [](const glimmer::Light& l) { return l.type == glimmer::LightType::Sphere; }), 2);
    EXPECT_EQ(std::count_if(s.lights.begin(), s.lights.end(), [](const glimmer::Light& l) { return l.type == glimmer::LightType::Rect; }), 1);
    EXPECT_GE(s.cameras.size(), 5u);
    ASSERT_EQ(s.walkthrough.size(), s.cameras.size());
    for (const std::string& name : s.walkthrough) EXPECT_NO_THROW(s.camera(name));
    EXPECT_NO_THROW(s.camera("grazing"));
}

// UVs are metres along the surface: every triangle's UV area equals its surface area (up to tessellation),
// and frames are orthonormal and follow the UV directions.
TEST(ScenesAtrium, UvsAreMetresAlongSurfaces) {
    const Scene& s = atriumScene();
    for (const glimmer::MeshData& mesh : s.meshes) {
        SCOPED_TRACE(mesh.name);
        expectValidFrames(mesh, mesh.name);
        // The relief's grid UVs follow arc lengths along rows and columns, which steep relief slopes shear:
        // looser bound there.
        const double tolerance = mesh.name == "relief" ? 0.5 : 0.1;
        double worldTotal = 0.0, uvTotal = 0.0;
        size_t outliers = 0, counted = 0;
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
            double world = 0.5 * glm::length(glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]));
            glm::vec2 e1 = mesh.uvs[b] - mesh.uvs[a], e2 = mesh.uvs[c] - mesh.uvs[a];
            double uv = 0.5 * std::abs(e1.x * e2.y - e1.y * e2.x);
            worldTotal += world;
            uvTotal += uv;
            if (world < 1e-6) continue;
            ++counted;
            outliers += std::abs(uv / world - 1.0) > tolerance;
            // Tangent of each corner along the triangle's own dP/du.
            float det = e1.x * e2.y - e2.x * e1.y;
            if (std::abs(det) < 1e-12f) continue;
            glm::vec3 dPdu = glm::normalize(((mesh.positions[b] - mesh.positions[a]) * e2.y - (mesh.positions[c] - mesh.positions[a]) * e1.y) / det);
            if (mesh.name != "relief") EXPECT_GT(glm::dot(dPdu, glm::vec3(mesh.tangents[a])), 0.9f) << "triangle " << i / 3;
        }
        EXPECT_NEAR(uvTotal / worldTotal, 1.0, 0.02);
        EXPECT_LE(outliers, counted / 100) << outliers << " of " << counted << " triangles stretched by more than " << tolerance;
    }
}

// At the grazing camera the floor's pixel footprints are long ellipses: the footprint AOV's red channel
// (major / minor axis) must exceed 16 on floor or snow pixels.
TEST(ScenesAtrium, GrazingCameraReachesHighFootprintAnisotropy) {
    const Scene& s = atriumScene();
    uint32_t floorId = 0, snowId = 0;
    for (uint32_t i = 0; i < s.materials.size(); ++i) {
        if (s.materials[i].name == "floor_tiles") floorId = i;
        if (s.materials[i].name == "snow") snowId = i;
    }
    glimmer::RenderRequest r = request("atrium", "grazing", "footprint");
    glimmer::OffscreenSession session(r);
    glimmer::RenderResult footprint = session.render(r);
    r.settings.debugView = glimmer::findAov("material").viewId;
    glimmer::RenderResult material = session.render(r);
    float maxRatio = 0.0f;
    size_t floorPixels = 0, above16 = 0;
    for (size_t i = 0; i + 3 < footprint.hdr.size(); i += 4) {
        if (material.hdr[i + 3] <= 0.0f) continue;   // sky
        uint32_t id = uint32_t(std::lround(material.hdr[i + 2]));
        if (id != floorId && id != snowId) continue;
        ++floorPixels;
        maxRatio = std::max(maxRatio, footprint.hdr[i]);
        above16 += footprint.hdr[i] > 16.0f;
    }
    EXPECT_GT(floorPixels, size_t(256 * 256 / 4)) << "the grazing view is mostly floor";
    EXPECT_GT(maxRatio, 16.0f);
    EXPECT_GT(above16, size_t(256)) << "more than a line of pixels";
}

// The atrium goldens' 8x8 block tolerance. With the same sources and the same Mesa (22.3.6-1+deb12u2), llvmpipe's
// atrium images differ between machines: the CI machine of 2026-12-02 (and the development machine of that day)
// were 2.61/255 off in one block of the objects camera and 2.19/255 of the overview, where the AMD EPYC machine of
// 2026-12-03 matches the references exactly (no other golden failed in that CI run). 4/255 covers that with margin;
// CamerasRenderTheCourtAndMatchGoldenImages below shows that changes a user would see still fail.
constexpr float kAtriumMachineDifference = 2.61f / 255.0f;
glimmer::test::GoldenOptions atriumGoldenOptions() {
    glimmer::test::GoldenOptions options;
    options.blockThreshold = 4.0f / 255.0f;
    return options;
}

// Every atrium camera at 256x256 (smooth method) in one session: the court fills the view with finite, varied
// radiance, and the image matches its golden (tests/support/golden.h; GLIMMER_UPDATE_GOLDEN=1 rewrites
// tests/golden/ref/atrium_<camera>.png). Then the widened tolerance still fails small regressions, by more than the
// machine difference (so a machine 2.61/255 off the reference fails them too): a fifth of a stop of exposure and a
// softer shadow filter (measured 10.19 and 11.31/255 in the worst block, 2026-12-03); GLIMMER_MEASURE=1 adds every
// light 15% weaker (10.06/255), which re-runs the sky's precompute. Neither change re-captures the reflection
// probes (a capture reads neither), so they cost a render each.
TEST(ScenesAtrium, CamerasRenderTheCourtAndMatchGoldenImages) {
    const Scene& s = atriumScene();
    glimmer::RenderRequest r = request("atrium", s.cameras.front().name);
    glimmer::OffscreenSession session(r);
    for (const glimmer::Camera& camera : s.cameras) {
        SCOPED_TRACE(camera.name);
        r.camera = camera.name;
        glimmer::RenderResult result = session.render(r);
        ImageStats stats = imageStats(result, s.skyColor);
        EXPECT_EQ(stats.nonFinite, 0u);
        EXPECT_GT(stats.coveredFraction, 0.4) << "the court fills most of every view";
        EXPECT_GT(stats.luminanceStdDev, 0.03);
        glimmer::test::GoldenComparison comparison = glimmer::test::compareWithGolden(
            "atrium_" + camera.name, result.display, result.width, result.height, atriumGoldenOptions());
        EXPECT_TRUE(comparison.passed) << comparison.message;
    }

    const std::string camera = "objects";
    const glimmer::RenderRequest base = request("atrium", camera);
    std::vector<const char*> changes = {"exposure=0.2", "shadow.filter_radius=4"};
    if (glimmer::test::fullMeasurement()) changes.push_back("light.intensity=0.85");
    const std::vector<uint8_t> reference = glimmer::test::readGolden("atrium_" + camera);
    for (const char* change : changes) {
        SCOPED_TRACE(change);
        glimmer::RenderRequest changed = base;
        changed.settings.apply(change);
        glimmer::RenderResult result = session.render(changed);
        ASSERT_EQ(reference.size(), result.display.size());
        glimmer::test::GoldenComparison comparison = glimmer::test::compareImages(
            reference, result.display, result.width, result.height, atriumGoldenOptions());
        EXPECT_FALSE(comparison.passed) << comparison.message;
        EXPECT_GT(comparison.maxBlockError, atriumGoldenOptions().blockThreshold + kAtriumMachineDifference)
            << comparison.message;
    }
}
