// Khronos glTF test models (../shared/assets/models/khronos-tests/, each folder's README says what a correct
// render shows) rendered through the real pipeline and checked against what their READMEs describe; skipped
// when ../shared is absent. Renders are small (160-192 px): the checks sample regions found by projecting the
// model's own geometry through the camera, not fixed pixel positions.
#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/image_io.h"
#include "render/aov.h"
#include "offscreen/offscreen.h"
#include "scene/camera.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "support/process.h"

namespace fs = std::filesystem;
using glimmer::RenderRequest;
using glimmer::RenderResult;
using glimmer::Scene;

namespace {

fs::path khronosModel(const std::string& name) {
    std::string shared = glimmer::test::sharedAssetsDir();
    if (shared.empty()) return {};
    return fs::path(shared) / "models" / "khronos-tests" / name / (name + ".gltf");
}

#define KHRONOS_MODEL(var, name)                                                      \
    const fs::path var = khronosModel(name);                                          \
    if (var.empty() || !fs::exists(var)) GTEST_SKIP() << "../shared/assets absent: " << name

RenderRequest request(const fs::path& model, const std::string& aov, int size, const glimmer::Camera& camera) {
    RenderRequest r;
    r.scene = model.string();
    r.cameraOverride = camera;
    r.width = r.height = size;
    r.settings.method = "smooth";
    r.settings.debugView = glimmer::findAov(aov).viewId;
    r.environment = "none";
    return r;
}

// A camera on +z (or `direction`) looking at the centre of the scene's bounds, framing them.
glimmer::Camera frontCamera(const Scene& scene, glm::vec3 direction = {0, 0, 1}, float margin = 1.15f) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const auto& instance : scene.instances)
        for (const glm::vec3& p : scene.meshes[instance.mesh].positions) {
            glm::vec3 w = glm::vec3(instance.transform * glm::vec4(p, 1.0f));
            lo = glm::min(lo, w);
            hi = glm::max(hi, w);
        }
    glimmer::Camera c;
    c.name = "test";
    c.target = 0.5f * (lo + hi);
    float radius = 0.5f * glm::length(hi - lo);
    c.verticalFovDegrees = 30.0f;
    c.position = c.target + glm::normalize(direction) * radius * margin / std::tan(glm::radians(15.0f));
    c.up = std::abs(glm::normalize(direction).y) > 0.9f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    c.nearPlane = radius * 0.01f;
    return c;
}

// Pixel (x right, y up: the HDR is bottom-up) of a world point.
glm::vec2 project(const glimmer::Camera& camera, int width, int height, glm::vec3 world) {
    glm::vec4 clip = camera.projection(float(width) / float(height)) * camera.view() * glm::vec4(world, 1.0f);
    glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {(ndc.x * 0.5f + 0.5f) * float(width), (ndc.y * 0.5f + 0.5f) * float(height)};
}

glm::vec4 at(const RenderResult& r, int x, int y) {
    x = std::clamp(x, 0, r.width - 1);
    y = std::clamp(y, 0, r.height - 1);
    const float* p = &r.hdr[(size_t(y) * size_t(r.width) + size_t(x)) * 4];
    return {p[0], p[1], p[2], p[3]};
}

// World bounds of one instance.
struct Box { glm::vec3 lo{1e30f}, hi{-1e30f}; glm::vec3 centre() const { return 0.5f * (lo + hi); } };
Box instanceBounds(const Scene& scene, size_t instance) {
    Box b;
    const auto& in = scene.instances[instance];
    for (const glm::vec3& p : scene.meshes[in.mesh].positions) {
        glm::vec3 w = glm::vec3(in.transform * glm::vec4(p, 1.0f));
        b.lo = glm::min(b.lo, w);
        b.hi = glm::max(b.hi, w);
    }
    return b;
}

// Mean of the pixels whose centres project inside the world-space rectangle [lo, hi] (x, y; at depth z) and
// whose alpha says geometry was drawn; `count` is how many.
glm::vec3 meanOver(const RenderResult& r, const glimmer::Camera& camera, glm::vec2 lo, glm::vec2 hi, float z, int* count = nullptr) {
    glm::vec2 a = project(camera, r.width, r.height, {lo.x, lo.y, z}), b = project(camera, r.width, r.height, {hi.x, hi.y, z});
    glm::ivec2 p0 = glm::ivec2(glm::ceil(glm::min(a, b))), p1 = glm::ivec2(glm::floor(glm::max(a, b)));
    glm::vec3 sum(0.0f);
    int n = 0;
    for (int y = p0.y; y < p1.y; ++y)
        for (int x = p0.x; x < p1.x; ++x) {
            glm::vec4 c = at(r, x, y);
            if (c.w <= 0.0f) continue;
            sum += glm::vec3(c);
            ++n;
        }
    if (count) *count = n;
    return n ? sum / float(n) : glm::vec3(0.0f);
}

// The display image of a render, kept in build/test-output/khronos/ to be looked at next to the model's ref_*.
void keep(const RenderResult& r, const std::string& name) {
    fs::path dir = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "khronos";
    fs::create_directories(dir);
    glimmer::writePng(dir / (name + ".png"), r.display.data(), r.width, r.height);
}

std::string writeFile(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// NormalTangentTest: no TANGENTs in the file, so the frames are generated; glTF's v runs down the image and its
// normal maps are +Y up. The README: the normal-mapped cells (right of each pair) must reflect like the real
// domes (left): their normals point up on the upper half and down on the lower half of each cell. The test
// compares the normal AOV of each normal-mapped cell with its geometric twin, quadrant by quadrant.
TEST(KhronosConformance, NormalTangentTestNormalMapsMatchTheRealDomes) {
    KHRONOS_MODEL(model, "NormalTangentTest");
    Scene scene = glimmer::loadGltfScene(model);
    glimmer::Camera camera = frontCamera(scene, {0, 0, 1}, 1.0f);
    RenderResult normals = glimmer::renderOffscreen(request(model, "normal", 192, camera));
    keep(normals, "NormalTangentTest_normal");
    // Layout read from the file's vertices: 3 pairs x 5 rows of 0.3 m cells on the z = 0 panel; the real dome
    // (radius 0.1 m) of pair p, row r is centred at (-0.96 + 0.8 p, -0.8 + 0.4 r), its normal-mapped twin 0.32 m
    // to the right.
    int checked = 0;
    for (int row = 0; row < 5; ++row)
        for (int pair = 0; pair < 3; ++pair) {
            const glm::vec2 centre(-0.96f + 0.8f * float(pair), -0.8f + 0.4f * float(row));
            for (glm::vec2 side : {glm::vec2(0, 1), glm::vec2(0, -1), glm::vec2(1, 0), glm::vec2(-1, 0)}) {
                auto quadrant = [&](glm::vec2 c) {
                    glm::vec2 mid = c + side * 0.055f, half = glm::abs(glm::vec2(side.y, side.x)) * 0.04f + glm::abs(side) * 0.02f;
                    int n = 0;
                    glm::vec3 mean = meanOver(normals, camera, mid - half, mid + half, 0.0f, &n);
                    EXPECT_GT(n, 0);
                    return mean;
                };
                glm::vec3 real = quadrant(centre), mapped = quadrant(centre + glm::vec2(0.32f, 0.0f));
                SCOPED_TRACE("row " + std::to_string(row) + " pair " + std::to_string(pair) + " side " +
                             std::to_string(int(side.x)) + "," + std::to_string(int(side.y)));
                const float realAlong = glm::dot(glm::vec2(real), side), mappedAlong = glm::dot(glm::vec2(mapped), side);
                EXPECT_GT(realAlong, 0.2f) << "the real dome's normals lean outwards";
                EXPECT_GT(mappedAlong, 0.2f) << "normal-mapped normals lean outwards (up on the upper half)";
                EXPECT_NEAR(mapped.x, real.x, 0.2f);
                EXPECT_NEAR(mapped.y, real.y, 0.2f);
                ++checked;
            }
        }
    EXPECT_EQ(checked, 60);
}

// ---------------------------------------------------------------------------------------------------------------
// Generated models for the exact formulas (no ../shared needed): quads facing +z, one material each.
namespace {

struct QuadSpec {
    float z;              // plane of the quad
    float halfSize;       // half its side
    std::string material; // glTF material JSON
};

// Writes dir/name.gltf + name.bin with one node per quad (in the order given) and returns the .gltf path.
fs::path writeQuads(const fs::path& dir, const std::string& name, const std::vector<QuadSpec>& quads,
                    const std::string& extensionsUsed = "") {
    fs::create_directories(dir);
    std::string bin;
    auto put = [&](const void* p, size_t n) { bin.append(static_cast<const char*>(p), n); };
    // Shared normals (48 bytes), UVs (32), indices (12, padded to 12): offsets 0, 48, 80.
    const float normals[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const float uvs[8] = {0, 1, 1, 1, 1, 0, 0, 0};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    put(normals, sizeof normals);
    put(uvs, sizeof uvs);
    put(indices, sizeof indices);
    std::ostringstream views, accessors, meshes, nodes, materials;
    views << R"({"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":32},{"buffer":0,"byteOffset":80,"byteLength":12})";
    accessors << R"({"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},{"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"},{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"})";
    for (size_t i = 0; i < quads.size(); ++i) {
        const float h = quads[i].halfSize, z = quads[i].z;
        const float p[12] = {-h, -h, z, h, -h, z, h, h, z, -h, h, z};
        size_t offset = bin.size();
        put(p, sizeof p);
        views << R"(,{"buffer":0,"byteOffset":)" << offset << R"(,"byteLength":48})";
        accessors << R"(,{"bufferView":)" << 3 + i << R"(,"componentType":5126,"count":4,"type":"VEC3","min":[)" << -h << ","
                  << -h << "," << z << "],\"max\":[" << h << "," << h << "," << z << "]}";
        meshes << (i ? "," : "") << R"({"primitives":[{"attributes":{"POSITION":)" << 3 + i
               << R"(,"NORMAL":0,"TEXCOORD_0":1},"indices":2,"material":)" << i << "}]}";
        nodes << (i ? "," : "") << R"({"mesh":)" << i << "}";
        materials << (i ? "," : "") << quads[i].material;
    }
    std::ostringstream sceneNodes;
    for (size_t i = 0; i < quads.size(); ++i) sceneNodes << (i ? "," : "") << i;
    std::ostringstream gltf;
    gltf << R"({"asset":{"version":"2.0"},)" << extensionsUsed << R"("buffers":[{"byteLength":)" << bin.size() << R"(,"uri":")"
         << name << R"(.bin"}],"bufferViews":[)" << views.str() << R"(],"accessors":[)" << accessors.str()
         << R"(],"meshes":[)" << meshes.str() << R"(],"nodes":[)" << nodes.str() << R"(],"scenes":[{"nodes":[)"
         << sceneNodes.str() << R"(]}],"materials":[)" << materials.str() << "]}";
    writeFile(dir / (name + ".bin"), bin);
    writeFile(dir / (name + ".gltf"), gltf.str());
    return dir / (name + ".gltf");
}

glimmer::Camera cameraOnZ(float distance) {
    glimmer::Camera c;
    c.name = "test";
    c.position = {0.0f, 0.0f, distance};
    c.target = {0.0f, 0.0f, 0.0f};
    c.verticalFovDegrees = 40.0f;
    c.nearPlane = 0.05f;
    return c;
}

RenderResult renderFinal(const fs::path& model, const glimmer::Camera& camera, int size = 64, const std::string& env = "none") {
    RenderRequest r = request(model, "final", size, camera);
    r.environment = env;
    // Ambient occlusion off: the screen-space term darkens the opaque renders that stand in for each glass layer,
    // and the forward pass of blended surfaces (no G-buffer depth of its own) is not occluded.
    r.settings.apply("ao.enabled=0");
    return glimmer::renderOffscreen(r);
}

}  // namespace

// glTF 3.9.2 + KHR_materials_emissive_strength: emitted radiance = emissiveFactor x emissiveStrength x
// emissiveTexture (sRGB-decoded), added to the reflected radiance. The same quad rendered with and without
// emission must differ by exactly that, in every pixel it covers (HDR output, 32-bit float).
TEST(KhronosConformance, EmissiveRadianceIsFactorTimesStrengthTimesTexture) {
    fs::path dir = glimmer::test::makeTempDir("khronos_emissive");
    // A 4x4 emissive texture of one sRGB colour (200, 100, 50): linear (0.5776, 0.1274, 0.0319).
    std::vector<uint8_t> texel(4 * 4 * 4);
    for (size_t i = 0; i < texel.size(); i += 4) { texel[i] = 200; texel[i + 1] = 100; texel[i + 2] = 50; texel[i + 3] = 255; }
    glimmer::writePng(dir / "emit.png", texel.data(), 4, 4);
    auto srgbToLinear = [](float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); };
    const glm::vec3 texture(srgbToLinear(200 / 255.0f), srgbToLinear(100 / 255.0f), srgbToLinear(50 / 255.0f));
    const std::string base = R"("pbrMetallicRoughness":{"baseColorFactor":[0.3,0.3,0.3,1],"metallicFactor":0,"roughnessFactor":0.7})";
    const std::string plain = "{" + base + "}";
    const std::string emissive = "{" + base + R"(,"emissiveFactor":[0.2,0.5,0.8],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":3.5}}})";
    const std::string textured = "{" + base + R"(,"emissiveFactor":[1,0.5,0.25],"emissiveTexture":{"index":0}})";
    const std::string used = R"("extensionsUsed":["KHR_materials_emissive_strength"],"images":[{"uri":"emit.png"}],"textures":[{"source":0}],)";
    glimmer::Camera camera = cameraOnZ(3.0f);
    RenderResult off = renderFinal(writeQuads(dir, "off", {{0.0f, 1.0f, plain}}, used), camera);
    RenderResult on = renderFinal(writeQuads(dir, "on", {{0.0f, 1.0f, emissive}}, used), camera);
    RenderResult tex = renderFinal(writeQuads(dir, "tex", {{0.0f, 1.0f, textured}}, used), camera);
    const glm::vec3 expectedOn = glm::vec3(0.2f, 0.5f, 0.8f) * 3.5f, expectedTex = glm::vec3(1.0f, 0.5f, 0.25f) * texture;
    int covered = 0;
    double worst = 0.0;
    for (int y = 0; y < off.height; ++y)
        for (int x = 0; x < off.width; ++x) {
            if (at(off, x, y).w <= 0.0f) continue;   // background
            ++covered;
            glm::vec3 base3 = glm::vec3(at(off, x, y));
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst, double(std::abs(at(on, x, y)[c] - base3[c] - expectedOn[c])));
                worst = std::max(worst, double(std::abs(at(tex, x, y)[c] - base3[c] - expectedTex[c])));
            }
        }
    EXPECT_GT(covered, 200);
    // Float sums of O(1) values; the texture's 8-bit sRGB decode is exact in the GL (GL_SRGB8_ALPHA8).
    EXPECT_LT(worst, 2e-3) << "emitted radiance differs from factor x strength x texture";
    std::printf("emission: %d pixels, worst |L_on - L_off - E| = %.2e\n", covered, worst);
}

// glTF 3.9.4 BLEND: the shaded surface S with alpha a is composited over what lies behind, C = a S + (1 - a) B,
// back to front. Two glass quads (alpha 0.4 and 0.7, listed near-first in the file so only sorting puts them in
// order) over an opaque backdrop: C = a2 S2 + (1 - a2) (a1 S1 + (1 - a1) B), where B, S1 and S2 are measured by
// rendering the backdrop alone and each glass quad as an opaque material at the same place.
TEST(KhronosConformance, BlendedGlassMatchesTheCompositingFormula) {
    fs::path dir = glimmer::test::makeTempDir("khronos_blend");
    const std::string backdrop = R"({"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.8,0.2,1],"metallicFactor":0,"roughnessFactor":0.9}})";
    auto glass = [](const char* rgb, float a, bool blend) {
        return std::string(R"({"pbrMetallicRoughness":{"baseColorFactor":[)") + rgb + "," + std::to_string(a) +
               R"(],"metallicFactor":0,"roughnessFactor":0.5},"doubleSided":true)" + (blend ? R"(,"alphaMode":"BLEND"})" : "}");
    };
    const float a1 = 0.4f, a2 = 0.7f;
    // Colours k/255 and roughness 0.5 (alpha 0.25): exact in the G-buffer's RGBA8 / RGBA16F targets, so the opaque
    // renders that measure S1 and S2 hold the very material the forward pass shades.
    const char* rgb1 = "0.2,0.4,1.0";
    const char* rgb2 = "0.8,0.2,0.2";
    glimmer::Camera camera = cameraOnZ(4.0f);
    // No environment map (its precomputation would cost ~5 s per render here): the constant ambient and the
    // model's default lights light every layer, in the forward pass as in the lighting pass.
    const std::string env = "none";
    RenderResult composite = renderFinal(writeQuads(dir, "composite", {{0.6f, 0.6f, glass(rgb2, a2, true)},
                                                                       {0.3f, 0.8f, glass(rgb1, a1, true)},
                                                                       {0.0f, 1.2f, backdrop}}), camera, 64, env);
    RenderResult b = renderFinal(writeQuads(dir, "backdrop", {{0.0f, 1.2f, backdrop}}), camera, 64, env);
    RenderResult s1 = renderFinal(writeQuads(dir, "s1", {{0.3f, 0.8f, glass(rgb1, 1.0f, false)}}), camera, 64, env);
    RenderResult s2 = renderFinal(writeQuads(dir, "s2", {{0.6f, 0.6f, glass(rgb2, 1.0f, false)}}), camera, 64, env);
    int both = 0, one = 0;
    double worst = 0.0;
    for (int y = 0; y < b.height; ++y)
        for (int x = 0; x < b.width; ++x) {
            bool in1 = at(s1, x, y).w > 0.0f, in2 = at(s2, x, y).w > 0.0f;
            if (at(b, x, y).w <= 0.0f || !in1) continue;
            glm::vec3 expected = a1 * glm::vec3(at(s1, x, y)) + (1.0f - a1) * glm::vec3(at(b, x, y));
            if (in2) expected = a2 * glm::vec3(at(s2, x, y)) + (1.0f - a2) * expected;
            (in2 ? both : one) += 1;
            glm::vec3 got = glm::vec3(at(composite, x, y));
            for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(got[c] - expected[c]) / std::max(expected[c], 1e-2f)));
        }
    EXPECT_GT(both, 100);
    EXPECT_GT(one, 100);
    // Blending happens in the RGBA32F HDR target; S is shaded by the forward program, which evaluates the
    // lighting pass's formulas (same lights, same prefiltered environment) in its own float arithmetic.
    EXPECT_LT(worst, 5e-3) << "composite differs from a2 S2 + (1 - a2)(a1 S1 + (1 - a1) B)";
    std::printf("blend: %d pixels behind two layers, %d behind one, worst relative error %.2e\n", both, one, worst);
}

// KHR_materials_clearcoat "Emission": the coat lies on top of the emission, coated_emission = emission x
// (1 - c Fc), Fc the coat's Schlick Fresnel (F0 0.04) at n.v. A coated (c = 1) quad with and without emission:
// the difference is E (1 - Fc(n.v)) pixel by pixel, n = +z, v from the camera ray.
TEST(KhronosConformance, EmissionUnderAClearCoatIsDimmedByTheCoatFresnel) {
    fs::path dir = glimmer::test::makeTempDir("khronos_coated_emission");
    const std::string coat = R"("extensions":{"KHR_materials_clearcoat":{"clearcoatFactor":1.0,"clearcoatRoughnessFactor":0.5}})";
    const std::string base = R"("pbrMetallicRoughness":{"baseColorFactor":[0.3,0.3,0.3,1],"metallicFactor":0,"roughnessFactor":0.7})";
    const std::string used = R"("extensionsUsed":["KHR_materials_clearcoat"],)";
    glimmer::Camera camera = cameraOnZ(3.0f);
    RenderResult off = renderFinal(writeQuads(dir, "off", {{0.0f, 1.0f, "{" + base + "," + coat + "}"}}, used), camera);
    RenderResult on = renderFinal(writeQuads(dir, "on", {{0.0f, 1.0f, "{" + base + R"(,"emissiveFactor":[0.2,0.5,0.8],)" + coat + "}"}}, used), camera);
    const glm::dvec3 emission(0.2, 0.5, 0.8);
    int covered = 0;
    double worst = 0.0, largestDimming = 0.0;
    for (int y = 0; y < off.height; ++y)
        for (int x = 0; x < off.width; ++x) {
            if (at(off, x, y).w <= 0.0f) continue;
            ++covered;
            glimmer::Ray ray = glimmer::cameraRay(camera, off.width, off.height, x + 0.5, y + 0.5);
            double nDotV = -ray.direction.z;
            double fresnel = 0.04 + 0.96 * std::pow(1.0 - nDotV, 5.0);
            largestDimming = std::max(largestDimming, fresnel);
            for (int c = 0; c < 3; ++c) {
                double expected = emission[c] * (1.0 - fresnel);
                worst = std::max(worst, std::abs(double(at(on, x, y)[c] - at(off, x, y)[c]) - expected));
            }
        }
    EXPECT_GT(covered, 200);
    EXPECT_GT(largestDimming * emission.z, 10 * 2e-3);   // the coat dims the blue channel 16x the tolerance or more
    EXPECT_LT(worst, 2e-3) << "coated emission differs from E (1 - c Fc)";
    std::printf("coated emission: %d pixels, worst |L_on - L_off - E (1 - Fc)| = %.2e\n", covered, worst);
}

// A coated alpha-BLEND surface (forward pass) is the coated opaque surface (lighting pass, against the CPU
// two-lobe BRDF in Clearcoat.*) composited over the backdrop: C = a S_coated + (1 - a) B. Coat values 0.5 are
// exact in the G-buffer's half floats, so both passes shade the same coat.
TEST(KhronosConformance, ClearCoatedGlassIsTheCoatedSurfaceComposited) {
    fs::path dir = glimmer::test::makeTempDir("khronos_coated_blend");
    const std::string backdrop = R"({"pbrMetallicRoughness":{"baseColorFactor":[0.9,0.8,0.2,1],"metallicFactor":0,"roughnessFactor":0.9}})";
    auto glass = [](float a, bool blend, bool coated) {
        return std::string(R"({"pbrMetallicRoughness":{"baseColorFactor":[0.2,0.4,1.0,)") + std::to_string(a) +
               R"(],"metallicFactor":0,"roughnessFactor":0.5},"doubleSided":true)" +
               (coated ? R"(,"extensions":{"KHR_materials_clearcoat":{"clearcoatFactor":1.0,"clearcoatRoughnessFactor":0.5}})" : "") +
               (blend ? R"(,"alphaMode":"BLEND"})" : "}");
    };
    const std::string used = R"("extensionsUsed":["KHR_materials_clearcoat"],)";
    const float a = 0.6f;
    glimmer::Camera camera = cameraOnZ(4.0f);
    RenderResult composite = renderFinal(writeQuads(dir, "composite", {{0.4f, 0.8f, glass(a, true, true)},
                                                                       {0.0f, 1.2f, backdrop}}, used), camera);
    RenderResult b = renderFinal(writeQuads(dir, "backdrop", {{0.0f, 1.2f, backdrop}}), camera);
    RenderResult s = renderFinal(writeQuads(dir, "coated", {{0.4f, 0.8f, glass(1.0f, false, true)}}, used), camera);
    RenderResult bare = renderFinal(writeQuads(dir, "bare", {{0.4f, 0.8f, glass(1.0f, false, false)}}), camera);
    int covered = 0;
    double worst = 0.0, coatEffect = 0.0;
    for (int y = 0; y < b.height; ++y)
        for (int x = 0; x < b.width; ++x) {
            if (at(b, x, y).w <= 0.0f || at(s, x, y).w <= 0.0f) continue;
            ++covered;
            glm::vec3 expected = a * glm::vec3(at(s, x, y)) + (1.0f - a) * glm::vec3(at(b, x, y));
            glm::vec3 got = glm::vec3(at(composite, x, y));
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst, double(std::abs(got[c] - expected[c]) / std::max(expected[c], 1e-2f)));
                coatEffect = std::max(coatEffect, double(std::abs(at(s, x, y)[c] - at(bare, x, y)[c]) /
                                                         std::max(at(bare, x, y)[c], 1e-2f)));
            }
        }
    EXPECT_GT(covered, 200);
    EXPECT_GT(coatEffect, 0.05);   // the coat changes the surface far more than the tolerance
    EXPECT_LT(worst, 5e-3) << "coated glass differs from a S_coated + (1 - a) B";
    std::printf("coated blend: %d pixels, worst relative error %.2e, coat effect up to %.1f%%\n", covered, worst,
                100.0 * coatEffect);
}

// ---------------------------------------------------------------------------------------------------------------
// Loader-level checks (no GL): label fast.

namespace {
std::vector<std::string> linesContaining(const std::string& text, const std::string& needle) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (line.find(needle) != std::string::npos) out.push_back(line);
    return out;
}
const glimmer::Material& materialNamed(const Scene& scene, const std::string& name) {
    for (const auto& m : scene.materials)
        if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
}
}  // namespace

// A missing image used by two materials gives one warning line that names the file and says it was not found;
// none of tinygltf's own lines ("File not found : ", "Failed to load external 'uri'"). Used as the emissive
// texture of two more materials, it turns their emission off with one more line for the whole model (the factor
// alone would light the whole surface), not one per material.
TEST(KhronosLoader, MissingImageGivesOneWarningNamingTheFile) {
    fs::path dir = glimmer::test::makeTempDir("khronos_missing_image");
    const std::string base = R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})";
    const std::string emissive = R"({"emissiveFactor":[1,1,1],"emissiveTexture":{"index":0}})";
    const std::string images = R"("images":[{"uri":"not-there.png"}],"textures":[{"source":0}],)";
    fs::path model = writeQuads(dir, "missing", {{0.0f, 1.0f, base}, {0.5f, 0.5f, base}}, images);
    testing::internal::CaptureStderr();
    Scene scene = glimmer::loadGltfScene(model);
    std::string err = testing::internal::GetCapturedStderr();
    std::vector<std::string> lines = linesContaining(err, "");
    lines.erase(std::remove(lines.begin(), lines.end(), std::string()), lines.end());
    ASSERT_EQ(lines.size(), 1u) << err;
    EXPECT_NE(lines[0].find("missing.gltf"), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find("not-there.png"), std::string::npos) << lines[0];
    EXPECT_NE(lines[0].find("not found"), std::string::npos) << lines[0];
    EXPECT_EQ(err.find("File not found"), std::string::npos) << err;
    EXPECT_EQ(err.find("Failed to load external"), std::string::npos) << err;
    EXPECT_EQ(scene.materials[0].baseColorTexture, -1);

    fs::path emitting = writeQuads(dir, "emitting", {{0.0f, 1.0f, emissive}, {0.5f, 0.5f, emissive}, {0.7f, 0.2f, base}}, images);
    testing::internal::CaptureStderr();
    Scene e = glimmer::loadGltfScene(emitting);
    err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(linesContaining(err, "not-there.png").size(), 1u) << err;
    EXPECT_EQ(linesContaining(err, "emission").size(), 1u) << err;
    EXPECT_EQ(e.materials[0].emissive, glm::vec3(0.0f));
    EXPECT_EQ(e.materials[1].emissive, glm::vec3(0.0f));
}

// KHR_materials_emissive_strength multiplies emissiveFactor; a negative strength is a one-line error naming the
// material and the field; BLEND materials are marked for the transparent pass, not turned into masks.
TEST(KhronosLoader, EmissionStrengthAndBlendModeLoad) {
    fs::path dir = glimmer::test::makeTempDir("khronos_emission_load");
    fs::path model = writeQuads(dir, "emit", {{0.0f, 1.0f, R"({"emissiveFactor":[0.1,0.5,0.9],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":16}}})"},
                                              {0.5f, 0.5f, R"({"alphaMode":"BLEND","pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.25]}})"}},
                                R"("extensionsUsed":["KHR_materials_emissive_strength"],)");
    testing::internal::CaptureStderr();
    Scene scene = glimmer::loadGltfScene(model);
    std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(err, "") << "supported extension and features warn about nothing";
    EXPECT_NEAR(scene.materials[0].emissive.x, 1.6f, 1e-6f);
    EXPECT_NEAR(scene.materials[0].emissive.y, 8.0f, 1e-6f);
    EXPECT_NEAR(scene.materials[0].emissive.z, 14.4f, 1e-5f);
    EXPECT_TRUE(scene.materials[1].blend);
    EXPECT_LT(scene.materials[1].alphaCutoff, 0.0f) << "BLEND is no longer a 0.5 mask";
    fs::path bad = writeQuads(dir, "bad", {{0.0f, 1.0f, R"({"emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":-2}}})"}});
    try {
        glimmer::loadGltfScene(bad);
        ADD_FAILURE() << "negative emissiveStrength accepted";
    } catch (const glimmer::Error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("bad.gltf"), std::string::npos) << m;
        EXPECT_NE(m.find("materials[0]"), std::string::npos) << m;
        EXPECT_NE(m.find("emissiveStrength"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
}

// TextureSettingsTest's samplers (REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT per axis) and TextureTransformTest's
// (clamped, minFilter LINEAR: no mipmaps) reach the textures; images shared by textures with different samplers
// become separate textures.
TEST(KhronosLoader, SamplerWrapModesAndFiltersFollowTheFile) {
    KHRONOS_MODEL(settings, "TextureSettingsTest");
    Scene scene = glimmer::loadGltfScene(settings);
    using W = glimmer::TextureWrap;
    auto sampler = [&](const std::string& material) { return scene.textures.at(size_t(materialNamed(scene, material).baseColorTexture)).sampler; };
    EXPECT_EQ(sampler("TextureClampMaterialT").wrapS, W::Repeat);
    EXPECT_EQ(sampler("TextureClampMaterialT").wrapT, W::ClampToEdge);
    EXPECT_EQ(sampler("TextureClampMaterialS").wrapS, W::ClampToEdge);
    EXPECT_EQ(sampler("TextureClampMaterialS").wrapT, W::Repeat);
    EXPECT_EQ(sampler("TextureMirrorMaterialT").wrapT, W::MirroredRepeat);
    EXPECT_EQ(sampler("TextureMirrorMaterialS").wrapS, W::MirroredRepeat);
    EXPECT_EQ(sampler("TextureRepeatMaterialT").wrapS, W::ClampToEdge);   // RepeatTClampSSampler
    EXPECT_EQ(sampler("TextureRepeatMaterialT").wrapT, W::Repeat);
    EXPECT_TRUE(sampler("TextureRepeatMaterialT").mipmaps);
    EXPECT_FALSE(materialNamed(scene, "SingleSidedMaterial").doubleSided);
    EXPECT_TRUE(materialNamed(scene, "DoubleSidedMaterial").doubleSided);

    KHRONOS_MODEL(transform, "TextureTransformTest");
    Scene t = glimmer::loadGltfScene(transform);
    const auto& arrow = t.textures.at(size_t(materialNamed(t, "Rotation").baseColorTexture)).sampler;
    EXPECT_EQ(arrow.wrapS, W::ClampToEdge);
    EXPECT_EQ(arrow.wrapT, W::ClampToEdge);
    EXPECT_FALSE(arrow.mipmaps);
    const auto& marker = t.textures.at(size_t(materialNamed(t, "Correct").baseColorTexture)).sampler;
    EXPECT_EQ(marker.wrapS, W::Repeat);
    EXPECT_TRUE(marker.mipmaps);
}

// VertexColorTest's COLOR_0 (normalized unsigned shorts or floats, VEC4) is read per vertex, within [0, 1].
TEST(KhronosLoader, VertexColorsAreRead) {
    KHRONOS_MODEL(model, "VertexColorTest");
    Scene scene = glimmer::loadGltfScene(model);
    size_t withColors = 0;
    for (const auto& mesh : scene.meshes) {
        if (mesh.colors.empty()) continue;
        ++withColors;
        ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
        glm::vec4 lo(1.0f), hi(0.0f);
        for (const glm::vec4& c : mesh.colors) { lo = glm::min(lo, c); hi = glm::max(hi, c); }
        EXPECT_GE(lo.x, 0.0f);
        EXPECT_LE(hi.x, 1.0f);
        EXPECT_GT(hi.x - lo.x, 0.5f) << "red, green and blue vertex colours differ in red";
    }
    EXPECT_EQ(withColors, 1u);
}

// README: PNG output is sRGB-encoded. The albedo AOV's PNG (the display image) holds sRGB(base colour), its EXR
// (the HDR read-back) the linear base colour.
TEST(KhronosConformance, AlbedoAovPngIsSrgbEncoded) {
    fs::path dir = glimmer::test::makeTempDir("khronos_albedo");
    fs::path model = writeQuads(dir, "albedo", {{0.0f, 1.0f, R"({"pbrMetallicRoughness":{"baseColorFactor":[0.2,0.6,1.0,1]}})"}});
    RenderRequest r = request(model, "albedo", 32, cameraOnZ(2.0f));
    RenderResult result = glimmer::renderOffscreen(r);
    auto srgb = [](float c) { return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; };
    const glm::vec3 linear(0.2f, 0.6f, 1.0f);
    const size_t centre = (size_t(16) * 32 + 16) * 4;
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(result.hdr[centre + c], linear[c], 1.0f / 255.0f) << "channel " << c;
        EXPECT_NEAR(float(result.display[centre + c]), srgb(linear[c]) * 255.0f, 1.0f) << "channel " << c;
    }
}

// ---------------------------------------------------------------------------------------------------------------
// Region comparisons for the test models laid out as rows / columns of test and sample cells.
namespace {

// Fraction of covered pixels of the world rectangle [lo, hi] at depth z whose colour has no match within `tol`
// (max channel; relative for values above 1) among the 3x3 pixels around the same point shifted by `offset` (world): a one-pixel tolerance
// for the sub-pixel misalignment of the two cells.
double mismatchFraction(const RenderResult& r, const glimmer::Camera& camera, glm::vec2 lo, glm::vec2 hi, float z,
                        glm::vec2 offset, float tol, int* counted = nullptr) {
    glm::vec2 a = project(camera, r.width, r.height, {lo.x, lo.y, z}), b = project(camera, r.width, r.height, {hi.x, hi.y, z});
    glm::vec2 shift = project(camera, r.width, r.height, {lo.x + offset.x, lo.y + offset.y, z}) - a;
    glm::ivec2 p0 = glm::ivec2(glm::ceil(glm::min(a, b))), p1 = glm::ivec2(glm::floor(glm::max(a, b)));
    int n = 0, bad = 0;
    for (int y = p0.y; y < p1.y; ++y)
        for (int x = p0.x; x < p1.x; ++x) {
            glm::vec4 c = at(r, x, y);
            if (c.w <= 0.0f) continue;
            ++n;
            float best = 1e30f;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    glm::vec4 d = at(r, int(std::lround(x + shift.x)) + dx, int(std::lround(y + shift.y)) + dy);
                    best = std::min(best, std::max({std::abs(c.x - d.x), std::abs(c.y - d.y), std::abs(c.z - d.z)}));
                }
            // Relative above 1 (HDR radiance), absolute below.
            if (best > tol * std::max({1.0f, c.x, c.y, c.z})) ++bad;
        }
    if (counted) *counted = n;
    return n ? double(bad) / n : 1.0;
}

// Pixels of the rectangle that are clearly red (the test models' failure marks): r > 0.3 and r > ratio max(g, b);
// `greens` counts the clearly green ones the same way (lit images, where white light desaturates, use a lower ratio).
int redPixels(const RenderResult& r, const glimmer::Camera& camera, glm::vec2 lo, glm::vec2 hi, float z, int* greens = nullptr,
              float ratio = 3.0f) {
    glm::vec2 a = project(camera, r.width, r.height, {lo.x, lo.y, z}), b = project(camera, r.width, r.height, {hi.x, hi.y, z});
    glm::ivec2 p0 = glm::ivec2(glm::ceil(glm::min(a, b))), p1 = glm::ivec2(glm::floor(glm::max(a, b)));
    int red = 0, green = 0;
    for (int y = p0.y; y < p1.y; ++y)
        for (int x = p0.x; x < p1.x; ++x) {
            glm::vec4 c = at(r, x, y);
            if (c.x > 0.3f && c.x > ratio * std::max(c.y, c.z)) ++red;
            if (c.y > 0.15f && c.y > ratio * std::max(c.x, c.z)) ++green;
        }
    if (greens) *greens = green;
    return red;
}

}  // namespace

// NegativeScaleTest: the "scale -1.0" row (NegativeScaleFront, det -1, in front of NegativeScaleBack) must look
// like the "scale 1.0" row above it: front faces (clockwise after mirroring) drawn, back faces culled
// (doubleSided false), normals not flipped. And the mirrored spheres ("-1.0" column, two-sided, det -1 or +1
// under a mirrored parent) must be shaded like their unmirrored twins.
TEST(KhronosConformance, NegativeScaleTestMirroredRowMatchesTheUnmirroredOne) {
    KHRONOS_MODEL(model, "NegativeScaleTest");
    Scene scene = glimmer::loadGltfScene(model);
    glimmer::Camera camera = frontCamera(scene, {0, 0, 1}, 1.0f);
    glimmer::OffscreenSession session(request(model, "albedo", 192, camera));
    RenderResult albedo = session.render(request(model, "albedo", 192, camera));
    RenderResult normal = session.render(request(model, "normal", 192, camera));
    RenderResult lit = session.render(request(model, "final", 192, camera));
    keep(albedo, "NegativeScaleTest_albedo");
    keep(lit, "NegativeScaleTest_final");
    // Rows (world y): scale 1.0 over [2.23, 3.13], scale -1.0 over [1.07, 1.97]; columns front/back/sample over
    // x in [-0.44, 4.28]. Compared inside a margin of 0.05.
    const glm::vec2 lo(-0.39f, 2.28f), hi(4.23f, 3.08f), down(0.0f, -1.16f);
    int n = 0;
    // Edges of the checks and labels, resampled at a sub-pixel offset, account for the few per cent allowed; a
    // wrongly culled face (a red X over a quarter of its box) or flipped normals (a dark box) exceed it.
    const double allowed = 0.06;
    double m = mismatchFraction(albedo, camera, lo, hi, 0.1f, down, 0.1f, &n);
    EXPECT_LT(m, allowed) << "albedo: culling of the mirrored row";
    EXPECT_GT(n, 500);
    double mn = mismatchFraction(normal, camera, lo, hi, 0.1f, down, 0.1f), ml = mismatchFraction(lit, camera, lo, hi, 0.1f, down, 0.1f);
    EXPECT_LT(mn, allowed) << "normals of the mirrored row";
    EXPECT_LT(ml, allowed) << "lighting of the mirrored row";
    std::printf("NegativeScaleTest rows: %d pixels, mismatch albedo %.3f normal %.3f lit %.3f\n", n, m, mn, ml);
    EXPECT_EQ(redPixels(albedo, camera, {lo.x, 1.07f}, hi, 0.1f), 0) << "a red X shows: wrong face culled";
    // Spheres: rows at y = -1, -2.25, -3.5, "1.0" column at x = 1, "-1.0" at x = 3.
    for (float y : {-1.0f, -2.25f, -3.5f}) {
        SCOPED_TRACE("sphere row y " + std::to_string(y));
        EXPECT_LT(mismatchFraction(normal, camera, {0.7f, y - 0.3f}, {1.3f, y + 0.3f}, 0.5f, {2.0f, 0.0f}, 0.1f), 0.05);
        EXPECT_LT(mismatchFraction(lit, camera, {0.7f, y - 0.3f}, {1.3f, y + 0.3f}, 0.5f, {2.0f, 0.0f}, 0.1f), 0.05);
    }
}

// VertexColorTest: the "Test" row's checks are textures multiplied by red, green and blue COLOR_0, which zero
// the other channels (where the texture hides a cyan, magenta or yellow X); with vertex colours applied the row
// looks like the "Sample pass" row below it and shows no trace of the X's.
TEST(KhronosConformance, VertexColorTestChecksShowWithoutTheirX) {
    KHRONOS_MODEL(model, "VertexColorTest");
    Scene scene = glimmer::loadGltfScene(model);
    glimmer::Camera camera = frontCamera(scene, {0, 0, 1}, 1.0f);
    RenderResult albedo = glimmer::renderOffscreen(request(model, "albedo", 192, camera));
    keep(albedo, "VertexColorTest_albedo");
    // Checkmark boxes of the test row (world, z 0.04): x thirds around -0.62, 0, 0.62, y in [0.15, 0.55].
    const float boxZ = 0.04f;
    const float xs[3] = {-0.62f, 0.0f, 0.62f};
    for (int channel = 0; channel < 3; ++channel) {
        SCOPED_TRACE("check " + std::to_string(channel));
        glm::vec2 lo(xs[channel] - 0.14f, 0.22f), hi(xs[channel] + 0.14f, 0.48f);
        glm::vec2 a = project(camera, albedo.width, albedo.height, {lo.x, lo.y, boxZ});
        glm::vec2 b = project(camera, albedo.width, albedo.height, {hi.x, hi.y, boxZ});
        int lit = 0, stray = 0, n = 0;
        for (int y = int(std::ceil(a.y)); y < int(b.y); ++y)
            for (int x = int(std::ceil(a.x)); x < int(b.x); ++x) {
                glm::vec4 c = at(albedo, x, y);
                ++n;
                float own = c[channel], other = std::max(c[(channel + 1) % 3], c[(channel + 2) % 3]);
                if (own > 0.3f) ++lit;
                if (other > 0.1f) ++stray;
            }
        EXPECT_GT(n, 100);
        EXPECT_GT(lit, n / 20) << "the check in its own channel";
        EXPECT_LT(stray, n / 100 + 1) << "other channels must be zeroed by the vertex colour (no X)";
        std::printf("VertexColorTest check %d: %d pixels, %d lit, %d with other channels > 0.1\n", channel, n, lit, stray);
    }
}

// TextureSettingsTest: every box of the "Test" column must look like its "Sample pass" box (README): the
// single-sided row's wrong-way front quad culled, the double-sided one drawn, clamp / repeat / mirrored-repeat
// per axis. Each row's mesh spans both boxes: test at [x0, x0 + 0.9], sample at [x1 - 0.9, x1]. No red marks.
TEST(KhronosConformance, TextureSettingsTestBoxesMatchTheirSamples) {
    KHRONOS_MODEL(model, "TextureSettingsTest");
    Scene scene = glimmer::loadGltfScene(model);
    glimmer::Camera camera = frontCamera(scene, {0, 0, 1}, 1.0f);
    RenderResult albedo = glimmer::renderOffscreen(request(model, "albedo", 256, camera));
    keep(albedo, "TextureSettingsTest_albedo");
    int rows = 0;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const std::string& name = scene.materials[scene.instances[i].material].name;
        if (name == "BackgroundMaterial" || name == "LabelMaterial") continue;
        Box box = instanceBounds(scene, i);
        SCOPED_TRACE(name);
        ++rows;
        glm::vec2 lo(box.lo.x + 0.08f, box.lo.y + 0.08f), hi(box.lo.x + 0.82f, box.hi.y - 0.08f);
        glm::vec2 toSample(box.hi.x - 0.9f - box.lo.x, 0.0f);
        int n = 0, greens = 0;
        double m = mismatchFraction(albedo, camera, lo, hi, box.hi.z, toSample, 0.12f, &n);
        EXPECT_LT(m, 0.1) << "edges of the mipmapped checks differ by a few per cent; a wrong wrap mode by a third";
        EXPECT_GT(n, 60);
        std::printf("TextureSettingsTest %s: %d pixels, mismatch %.3f\n", name.c_str(), n, m);
        EXPECT_EQ(redPixels(albedo, camera, lo, hi, box.hi.z, &greens), 0) << "a red X or red block shows";
        EXPECT_GT(greens, n / 10) << "the green check or block";
    }
    EXPECT_EQ(rows, 8);
}

// ---------------------------------------------------------------------------------------------------------------
// TextureTransformTest: KHR_texture_transform (offset, rotation, scale, all three) with clamped, unmipmapped
// samplers. Every pixel of the six transformed quads must show the texel a CPU lookup predicts: the pixel
// centre's ray hits the quad, its barycentric UV goes through the material's transform, is clamped to the edge
// and bilinearly filtered from the decoded (sRGB -> linear) image. The README's markers follow from that.
namespace {

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

glm::vec3 clampedBilinear(const glimmer::TextureData& t, glm::vec2 uv) {
    auto texel = [&](int x, int y) {
        x = std::clamp(x, 0, t.width - 1);
        y = std::clamp(y, 0, t.height - 1);
        const uint8_t* p = &t.rgba[(size_t(y) * size_t(t.width) + size_t(x)) * 4];
        return glm::vec3(srgbToLinear(p[0] / 255.0f), srgbToLinear(p[1] / 255.0f), srgbToLinear(p[2] / 255.0f));
    };
    uv = glm::clamp(uv, 0.0f, 1.0f);
    glm::vec2 f = uv * glm::vec2(t.width, t.height) - 0.5f;
    glm::ivec2 i = glm::ivec2(glm::floor(f));
    glm::vec2 w = f - glm::floor(f);
    return glm::mix(glm::mix(texel(i.x, i.y), texel(i.x + 1, i.y), w.x), glm::mix(texel(i.x, i.y + 1), texel(i.x + 1, i.y + 1), w.x), w.y);
}

}  // namespace

TEST(KhronosConformance, TextureTransformTestTexelsFollowTheTransformAndClamp) {
    KHRONOS_MODEL(model, "TextureTransformTest");
    Scene scene = glimmer::loadGltfScene(model);
    glimmer::Camera camera = frontCamera(scene, {0, 0, 1}, 1.0f);
    RenderResult albedo = glimmer::renderOffscreen(request(model, "albedo", 192, camera));
    keep(albedo, "TextureTransformTest_albedo");
    const glm::mat4 inverseViewProjection = glm::inverse(camera.projection(1.0f) * camera.view());
    int quads = 0;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const auto& instance = scene.instances[i];
        const glimmer::Material& material = scene.materials[instance.material];
        if (material.name == "Correct" || material.name == "NotSupported" || material.name == "Error") continue;   // markers
        ASSERT_GE(material.baseColorTexture, 0) << material.name;
        const glimmer::TextureData& texture = scene.textures[size_t(material.baseColorTexture)];
        const glimmer::MeshData& mesh = scene.meshes[instance.mesh];
        SCOPED_TRACE(material.name);
        ++quads;
        Box box = instanceBounds(scene, i);
        glm::vec2 a = project(camera, albedo.width, albedo.height, box.lo), b = project(camera, albedo.width, albedo.height, box.hi);
        int n = 0, bad = 0, badIgnored = 0;
        // UV per pixel: the quads span one UV unit (before the transform) across their width.
        const float pixelUv = 1.0f / std::max(std::abs(b.x - a.x), 1.0f);
        for (int y = int(std::ceil(std::min(a.y, b.y))); y < int(std::max(a.y, b.y)); ++y)
            for (int x = int(std::ceil(std::min(a.x, b.x))); x < int(std::max(a.x, b.x)); ++x) {
                // The pixel centre's ray; the quad lies in a z = const plane.
                glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / glm::vec2(albedo.width, albedo.height) * 2.0f - 1.0f;
                glm::vec4 nearP = inverseViewProjection * glm::vec4(ndc, 1.0f, 1.0f);   // reversed Z: near plane at 1
                glm::vec3 origin = camera.position, direction = glm::normalize(glm::vec3(nearP) / nearP.w - origin);
                float s = (box.lo.z - origin.z) / direction.z;
                glm::vec3 hit = origin + s * direction;
                bool found = false;
                glm::vec2 uv(0.0f);
                for (size_t k = 0; k + 2 < mesh.indices.size() && !found; k += 3) {
                    glm::vec3 p[3];
                    for (int c = 0; c < 3; ++c) p[c] = glm::vec3(instance.transform * glm::vec4(mesh.positions[mesh.indices[k + c]], 1.0f));
                    glm::vec2 e1 = glm::vec2(p[1] - p[0]), e2 = glm::vec2(p[2] - p[0]), q = glm::vec2(hit - p[0]);
                    float det = e1.x * e2.y - e1.y * e2.x;
                    float u = (q.x * e2.y - q.y * e2.x) / det, v = (e1.x * q.y - e1.y * q.x) / det;
                    const float inset = 0.02f;   // away from the quad's edges (the G-buffer's coverage there is partial)
                    if (u < inset || v < inset || u + v > 1.0f - inset) continue;
                    found = true;
                    uv = (1.0f - u - v) * mesh.uvs[mesh.indices[k]] + u * mesh.uvs[mesh.indices[k + 1]] + v * mesh.uvs[mesh.indices[k + 2]];
                }
                if (!found) continue;
                glm::vec4 got = at(albedo, x, y);
                if (got.w <= 0.0f) continue;
                // A marker quad in front of the textured one (z + 0.01) covers some pixels: not this texture's.
                bool underMarker = false;
                for (size_t m = 0; m < scene.instances.size(); ++m) {
                    const std::string& mn = scene.materials[scene.instances[m].material].name;
                    if (mn != "Correct" && mn != "NotSupported" && mn != "Error") continue;
                    Box mb = instanceBounds(scene, m);
                    if (hit.x >= mb.lo.x - 0.02f && hit.x <= mb.hi.x + 0.02f && hit.y >= mb.lo.y - 0.02f && hit.y <= mb.hi.y + 0.02f) underMarker = true;
                }
                if (underMarker) continue;
                // The level-0 lookup of a minified, unmipmapped texture changes wholly across a texel edge, so the
                // comparison allows the UV to move by half a pixel's footprint (a one-pixel tolerance, in texture
                // space); a wrong offset, rotation, scale or wrap moves it by tens of pixels.
                ++n;
                float best = 1e30f;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        glm::vec2 jitter = glm::vec2(dx, dy) * 0.5f * pixelUv;
                        glm::vec3 expected = clampedBilinear(texture, glm::vec2(material.uvTransform * glm::vec3(uv + jitter, 1.0f)));
                        best = std::min(best, std::max({std::abs(got.x - expected.x), std::abs(got.y - expected.y), std::abs(got.z - expected.z)}));
                    }
                // RGBA8 G-buffer (linear) and bilinear weights of a different precision: a few percent.
                if (best > 0.06f) ++bad;
                // What a renderer ignoring the extension would show (the test must tell the two apart).
                glm::vec3 untransformed = clampedBilinear(texture, uv);
                if (std::max({std::abs(got.x - untransformed.x), std::abs(got.y - untransformed.y), std::abs(got.z - untransformed.z)}) > 0.06f) ++badIgnored;
            }
        EXPECT_GT(n, 400);
        // Measured: no pixel off (the sampler is unmipmapped, so one bilinear tap, as the CPU lookup); ignoring
        // the transform puts 45-98% off.
        EXPECT_LT(double(bad) / std::max(n, 1), 0.02) << bad << " of " << n << " pixels differ from the CPU lookup";
        EXPECT_GT(double(badIgnored) / std::max(n, 1), 0.25) << "the untransformed lookup would match as well";
        std::printf("TextureTransformTest %s: %d of %d pixels differ from the CPU lookup (%d from the untransformed one)\n",
                    material.name.c_str(), bad, n, badIgnored);
    }
    EXPECT_EQ(quads, 6);
}

// EmissiveStrengthTest: five cubes with emissiveFactor (0.1, 0.5, 0.9) and emissiveStrength 1, 2, 4, 8, 16 on a
// black base colour. Their front faces' radiance must grow by exactly the extra emission: L_k - L_1 =
// (s_k - 1) (0.1, 0.5, 0.9) (the reflected part, a dark dielectric's specular, is the same on every cube up to
// the slightly different view direction).
TEST(KhronosConformance, EmissiveStrengthTestCubesEmitFactorTimesStrength) {
    KHRONOS_MODEL(model, "EmissiveStrengthTest");
    Scene scene = glimmer::loadGltfScene(model);
    glimmer::Camera camera = frontCamera(scene, {0, 0, 1}, 1.0f);
    RenderResult lit = glimmer::renderOffscreen(request(model, "final", 192, camera));
    keep(lit, "EmissiveStrengthTest_final");
    const glm::vec3 factor(0.1f, 0.5f, 0.9f);
    const float strengths[5] = {1, 2, 4, 8, 16}, xs[5] = {-6, -3, 0, 3, 6};
    glm::vec3 first(0.0f);
    for (int k = 0; k < 5; ++k) {
        int n = 0;
        // The cubes are 1 m wide, centred on (x, 0, 0): sample the middle of their front face (z = 0.5).
        glm::vec3 l = meanOver(lit, camera, {xs[k] - 0.2f, -0.2f}, {xs[k] + 0.2f, 0.2f}, 0.5f, &n);
        ASSERT_GT(n, 4) << "cube " << k;
        if (k == 0) first = l;
        glm::vec3 expected = (strengths[k] - 1.0f) * factor;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(l[c] - first[c], expected[c], 0.01f + 0.005f * expected[c]) << "cube " << k << " channel " << c;
        EXPECT_GT(l.z, strengths[k] * factor.z * 0.99f) << "at least the emission";
    }
}

// AlphaBlendModeTest: under the "Blend" label a BLEND decal hides a red X in zero-alpha texels over a green check
// (drawn by the opaque label strip): composited correctly the X vanishes and the check shows; alpha used where the
// material is OPAQUE would instead blend away the "Opaque" check and show a red X. So: no red marks on the
// label strip, green under the blend decal.
TEST(KhronosConformance, AlphaBlendModeTestShowsChecksAndNoRedX) {
    KHRONOS_MODEL(model, "AlphaBlendModeTest");
    Scene scene = glimmer::loadGltfScene(model);
    glimmer::Camera camera = frontCamera(scene, {0, 0.6f, 1}, 0.8f);
    RenderResult lit = glimmer::renderOffscreen(request(model, "final", 256, camera));
    keep(lit, "AlphaBlendModeTest_final");
    int greens = 0;
    EXPECT_EQ(redPixels(lit, camera, {-1.21f, -0.05f}, {-0.99f, 0.07f}, 0.42f, &greens, 1.8f), 0) << "the blended decal's X shows";
    EXPECT_GT(greens, 0) << "the check under the blended decal (a few pixels at this size)";
    int stripGreens = 0;
    redPixels(lit, camera, {-3.29f, -0.09f}, {3.29f, 0.09f}, 0.41f, &stripGreens, 1.8f);
    glm::vec2 pa = project(camera, lit.width, lit.height, {-1.1f, 0.0f, 0.42f});
    std::printf("AlphaBlendModeTest: greens under the blend decal %d, on the strip %d, decal at pixel %.1f %.1f colour %.3f %.3f %.3f\n",
                greens, stripGreens, pa.x, pa.y, at(lit, int(pa.x), int(pa.y)).x, at(lit, int(pa.x), int(pa.y)).y, at(lit, int(pa.x), int(pa.y)).z);
    EXPECT_EQ(redPixels(lit, camera, {-3.29f, -0.09f}, {3.29f, 0.09f}, 0.41f, nullptr, 1.8f), 0) << "a red X on the label strip";
}
