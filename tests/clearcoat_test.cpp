// KHR_materials_clearcoat (issue 17): the loader reads every key and texture; the lighting pass's two-lobe
// layering against the CPU evaluation (engine/reference/clearcoat_reference.h); a coat of intensity 0 is no coat;
// a glint method's NDF is attenuated by the coat exactly like the smooth base.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/image_io.h"
#include "offscreen/offscreen.h"
#include "reference/brdf_reference.h"
#include "reference/clearcoat_reference.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(Clearcoat, GlContext);

using namespace glimmer;

namespace {

// A one-triangle glTF whose material holds `materialJson`; three 2x2 PNGs (coat.png, rough.png, normal.png) are
// textures 0, 1, 2.
std::string writeCoatedModel(const std::string& dir, const std::string& name, const std::string& materialJson) {
    float p[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
    float uv[6] = {0, 0, 1, 0, 0, 1};
    unsigned short idx[4] = {0, 2, 1, 0};
    std::string bin(reinterpret_cast<char*>(p), sizeof p);
    bin.append(reinterpret_cast<char*>(uv), sizeof uv);
    bin.append(reinterpret_cast<char*>(idx), sizeof idx);
    std::ofstream(dir + "/" + name + ".bin", std::ios::binary) << bin;
    // Distinct texels per image: coat red 200, roughness green 100, normal (128, 128, 255) = straight up.
    auto writeSolid = [&](const char* file, uint8_t r, uint8_t g, uint8_t b) {
        uint8_t rgba[16];
        for (int i = 0; i < 4; ++i) rgba[4 * i] = r, rgba[4 * i + 1] = g, rgba[4 * i + 2] = b, rgba[4 * i + 3] = 255;
        writePng(dir + "/" + file, rgba, 2, 2);
    };
    writeSolid("coat.png", 200, 0, 0);
    writeSolid("rough.png", 0, 100, 0);
    writeSolid("normal.png", 128, 128, 255);
    std::string path = dir + "/" + name + ".gltf";
    std::ofstream(path) << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_materials_clearcoat"],
 "buffers": [{"uri": ")" << name << R"(.bin", "byteLength": )" << bin.size() << R"(}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                 {"buffer": 0, "byteOffset": 60, "byteLength": 6}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 0, 1]},
               {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
               {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}],
 "images": [{"uri": "coat.png"}, {"uri": "rough.png"}, {"uri": "normal.png"}],
 "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
 "materials": [{"name": "paint", )" << materialJson << R"(}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
 "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
    return path;
}

std::string loadError(const std::string& path) {
    try {
        loadGltfScene(path);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(ClearcoatGltf, ReadsEveryKeyAndTexture) {
    std::string dir = test::makeTempDir("clearcoat_keys");
    Scene scene = loadGltfScene(writeCoatedModel(dir, "all", R"("extensions": {"KHR_materials_clearcoat": {
        "clearcoatFactor": 0.75, "clearcoatTexture": {"index": 0}, "clearcoatRoughnessFactor": 0.3,
        "clearcoatRoughnessTexture": {"index": 1}, "clearcoatNormalTexture": {"index": 2, "scale": 0.5}}})"));
    const Material& m = scene.materials.at(0);
    EXPECT_FLOAT_EQ(m.clearcoat, 0.75f);
    EXPECT_FLOAT_EQ(m.clearcoatRoughness, 0.3f);
    ASSERT_GE(m.clearcoatTexture, 0);
    ASSERT_GE(m.clearcoatRoughnessTexture, 0);
    ASSERT_GE(m.clearcoatNormalTexture, 0);
    EXPECT_EQ(scene.textures.at(size_t(m.clearcoatTexture)).rgba.at(0), 200);        // the coat image, linear
    EXPECT_FALSE(scene.textures.at(size_t(m.clearcoatTexture)).srgb);
    EXPECT_EQ(scene.textures.at(size_t(m.clearcoatRoughnessTexture)).rgba.at(1), 100);
    EXPECT_EQ(m.baseColorTexture, -1);
    // normalTextureInfo.scale is baked into the texture: (128, 128, 255) stays straight up at any scale, so the
    // scaled copy differs from the image only where x, y are non-zero; here the z channel must survive.
    const TextureData& normal = scene.textures.at(size_t(m.clearcoatNormalTexture));
    EXPECT_GE(normal.rgba.at(2), 250);

    Scene bare = loadGltfScene(writeCoatedModel(dir, "bare", R"("extensions": {"KHR_materials_clearcoat": {}})"));
    EXPECT_EQ(bare.materials.at(0).clearcoat, 0.0f);   // the extension's defaults: no coat
    EXPECT_EQ(bare.materials.at(0).clearcoatTexture, -1);
    Scene none = loadGltfScene(writeCoatedModel(dir, "none", R"("doubleSided": true)"));
    EXPECT_EQ(none.materials.at(0).clearcoat, 0.0f);
}

TEST(ClearcoatGltf, BadValuesNameTheField) {
    std::string dir = test::makeTempDir("clearcoat_bad");
    std::string e = loadError(writeCoatedModel(dir, "factor", R"("extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 2}})"));
    EXPECT_NE(e.find("materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor"), std::string::npos) << e;
    e = loadError(writeCoatedModel(dir, "rough", R"("extensions": {"KHR_materials_clearcoat": {"clearcoatRoughnessFactor": "x"}})"));
    EXPECT_NE(e.find("clearcoatRoughnessFactor is not a number in [0, 1]"), std::string::npos) << e;
    e = loadError(writeCoatedModel(dir, "tex", R"("extensions": {"KHR_materials_clearcoat": {"clearcoatTexture": {"index": 7}}})"));
    EXPECT_NE(e.find("clearcoatTexture.index 7 names no texture"), std::string::npos) << e;
}

namespace {

RenderRequest planeRequest(const std::string& scene, int size, std::initializer_list<const char*> settings) {
    RenderRequest request;
    request.scene = scene;
    request.width = request.height = size;
    request.environment = "none";   // constant ambient: the CPU reference's lighting
    for (const char* s : settings) request.settings.apply(s);
    return request;
}

}  // namespace

// Smooth base (no glints), one directional light, constant ambient: every sampled pixel of plane90 against
// base * (1 - c Fc) + c Fc (coat lobe * E + ambient) with the base from reference::shadeDirectional.
// The coat values are exact in the G-buffer's half floats (llvmpipe rounds 0.6 down to 0.5996, which moves a
// GGX peak by 0.3 %): the test judges the shading, not the storage.
TEST(Clearcoat, PlaneMatchesTwoLobeCpuBrdf) {
    const int size = 96;
    RenderResult result = renderOffscreen(planeRequest("plane90", size, {"material.glinty=0", "material.metallic=0.4",
        "material.alpha=0.25", "ambient=1", "material.clearcoat=0.75", "material.clearcoat_roughness=0.375"}));
    Scene scene = makeBuiltinScene("plane90");
    const Camera& camera = scene.cameras.front();
    const Light& light = scene.lights.front();
    reference::SurfacePoint surface;
    surface.baseColor = glm::round(glm::dvec3(scene.materials.front().baseColor) * 255.0) / 255.0;   // RGBA8 G-buffer
    surface.metallic = 0.4;
    surface.alpha = 0.25;
    reference::ClearcoatLayer coat;
    coat.clearcoat = 0.75;
    coat.roughness = 0.375;
    auto toShading = [](const glm::dvec3& v) { return glm::dvec3(v.x, v.z, v.y); };   // t = +x, b = +z, n = +y
    glm::dvec3 irradiance = glm::dvec3(light.color) * double(light.intensity), ambient(scene.skyColor);
    double worst = 0.0, worstCoatShare = 0.0;
    int checked = 0;
    for (int y = 5; y < size; y += 9)
        for (int x = 3; x < size; x += 9) {
            Ray ray = cameraRay(camera, size, size, x + 0.5, y + 0.5);
            glm::dvec3 wo = toShading(-ray.direction), wi = toShading(glm::normalize(glm::dvec3(light.vector)));
            glm::dvec3 base = reference::shadeDirectional(surface, wi, wo, irradiance, ambient);
            glm::dvec3 expected = reference::shadeClearcoat(coat, base, wi, wo, irradiance, ambient);
            worstCoatShare = std::max(worstCoatShare, glm::length(expected - base) / glm::length(base));
            size_t i = (size_t(y) * size + x) * 4;
            for (int c = 0; c < 3; ++c) {
                double err = std::abs(result.hdr[i + c] - expected[c]) / expected[c];
                worst = std::max(worst, err);
                EXPECT_LT(err, 1e-3) << "pixel " << x << "," << y << " channel " << c << ": " << result.hdr[i + c]
                                     << " expected " << expected[c] << " (uncoated " << base[c] << ")";
            }
            ++checked;
        }
    EXPECT_GT(checked, 80);
    EXPECT_GT(worstCoatShare, 0.1);   // the coat changes the image measurably (the test can see a missing coat)
    std::printf("clear coat plane: worst relative error %.2e over %d pixels; largest coat effect %.1f%%\n", worst,
                checked, 100.0 * worstCoatShare);
}

// Intensity 0 is the uncoated material bit for bit (a glinty one, through the method table); intensity 1 differs.
// And the coat attenuates the glint method's radiance exactly like the smooth base: with the coat normal equal to
// the base normal and no ambient, coated = uncoated * (1 - c Fc) + c Fc coat lobe E, pixel by pixel.
TEST(Clearcoat, ZeroIsNoCoatAndGlintsAreAttenuatedLikeTheBase) {
    const int size = 64;
    auto render = [&](std::initializer_list<const char*> coat) {
        RenderRequest request = planeRequest("plane90", size, {"ambient=0"});
        request.settings.method = "deliot2023";
        for (const char* s : coat) request.settings.apply(s);
        return renderOffscreen(request);
    };
    RenderResult plain = render({});
    RenderResult zero = render({"material.clearcoat=0", "material.clearcoat_roughness=0.7"});
    ASSERT_EQ(plain.hdr.size(), zero.hdr.size());
    EXPECT_TRUE(plain.hdr == zero.hdr) << "clear coat 0 changed the image";
    RenderResult coated = render({"material.clearcoat=1", "material.clearcoat_roughness=0.625"});

    Scene scene = makeBuiltinScene("plane90");
    const Camera& camera = scene.cameras.front();
    const Light& light = scene.lights.front();
    reference::ClearcoatLayer coat;
    coat.clearcoat = 1.0;
    coat.roughness = 0.625;
    auto toShading = [](const glm::dvec3& v) { return glm::dvec3(v.x, v.z, v.y); };
    glm::dvec3 irradiance = glm::dvec3(light.color) * double(light.intensity);
    double worst = 0.0, plainSum = 0.0, coatedSum = 0.0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            Ray ray = cameraRay(camera, size, size, x + 0.5, y + 0.5);
            glm::dvec3 wo = toShading(-ray.direction), wi = toShading(glm::normalize(glm::dvec3(light.vector)));
            size_t i = (size_t(y) * size + x) * 4;
            glm::dvec3 base(plain.hdr[i], plain.hdr[i + 1], plain.hdr[i + 2]);
            glm::dvec3 expected = reference::shadeClearcoat(coat, base, wi, wo, irradiance, glm::dvec3(0.0));
            for (int c = 0; c < 3; ++c) {
                double err = std::abs(coated.hdr[i + c] - expected[c]) / (expected[c] + 1e-3);
                worst = std::max(worst, err);
                if (err >= 1e-4) ADD_FAILURE() << "pixel " << x << "," << y << ": " << coated.hdr[i + c] << " expected " << expected[c];
            }
            plainSum += base.x;
            coatedSum += coated.hdr[i];
        }
    EXPECT_NE(plainSum, coatedSum);
    std::printf("glints under the coat: worst relative error %.2e over %d pixels\n", worst, size * size);
}

// The lighting program leaves the coat's terms out while no material of the scene is coated (SCENE_CLEARCOAT,
// render/frame/lighting_pass.h): one renderer that sees a coat appear and go (a material override) renders each
// image exactly as a fresh renderer does, so the program follows the scene both ways.
TEST(Clearcoat, LightingProgramFollowsTheScenesCoat) {
    RenderRequest plain = planeRequest("plane90", 48, {"ambient=0"});
    plain.settings.method = "deliot2023";
    RenderRequest coated = plain;
    coated.settings.apply("material.clearcoat=1");
    coated.settings.apply("material.clearcoat_roughness=0.3");
    const RenderResult freshPlain = renderOffscreen(plain), freshCoated = renderOffscreen(coated);
    OffscreenSession session(plain);
    const RenderResult first = session.render(plain);
    const RenderResult withCoat = session.render(coated);
    const RenderResult again = session.render(plain);
    EXPECT_TRUE(first.hdr == freshPlain.hdr);
    EXPECT_TRUE(withCoat.hdr == freshCoated.hdr) << "a coat that appeared after the first frame is not shaded";
    EXPECT_TRUE(again.hdr == freshPlain.hdr) << "the coat's removal did not restore the uncoated image";
    EXPECT_FALSE(freshCoated.hdr == freshPlain.hdr) << "the coat changes nothing (the test proves nothing)";
}

// The coat's environment lobe (default IBL mode, prefiltered): under a constant environment L and no light, a
// mirror-smooth coat adds c Fc L (its split-sum albedo A + B is 1 up to the table's precision) and scales the
// base by 1 - c Fc, pixel by pixel against the uncoated render.
TEST(Clearcoat, EnvironmentLobeReflectsAConstantSky) {
    const int size = 64;
    auto render = [&](std::initializer_list<const char*> coat) {
        RenderRequest request = planeRequest("plane90", size, {"material.glinty=0", "material.metallic=0.4",
            "material.alpha=0.25", "light.intensity=0", "ao.enabled=0", "probes.enabled=0"});
        request.environment = "constant:0.5,0.6,0.7";
        for (const char* s : coat) request.settings.apply(s);
        return renderOffscreen(request);
    };
    RenderResult plain = render({});
    RenderResult coated = render({"material.clearcoat=1", "material.clearcoat_roughness=0"});
    Scene scene = makeBuiltinScene("plane90");
    const Camera& camera = scene.cameras.front();
    reference::ClearcoatLayer coat;
    coat.clearcoat = 1.0;
    const glm::dvec3 sky(0.5, 0.6, 0.7);
    double worst = 0.0;
    for (int y = 2; y < size; y += 6)
        for (int x = 1; x < size; x += 6) {
            Ray ray = cameraRay(camera, size, size, x + 0.5, y + 0.5);
            double w = reference::clearcoatWeight(coat, -ray.direction.y);   // n_c = +y
            size_t i = (size_t(y) * size + x) * 4;
            for (int c = 0; c < 3; ++c) {
                double expected = plain.hdr[i + c] * (1.0 - w) + w * sky[c];
                double err = std::abs(coated.hdr[i + c] - expected) / expected;
                worst = std::max(worst, err);
                EXPECT_LT(err, 5e-3) << "pixel " << x << "," << y << ": " << coated.hdr[i + c] << " expected "
                                     << expected << " (uncoated " << plain.hdr[i + c] << ")";
            }
            EXPECT_GT(std::abs(coated.hdr[i] - plain.hdr[i]), 1e-3 * plain.hdr[i]);   // the coat is visible
        }
    std::printf("coat under a constant sky: worst relative error %.2e\n", worst);
}
