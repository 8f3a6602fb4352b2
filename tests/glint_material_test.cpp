// The one glint material (issue 17): glTF extension GLIMMER_materials_glint and its extras form, the mapping to
// each method's parameters, KHR_lights_punctual lights and cameras through both loading routes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "core/error.h"
#include "glints/glint_mapping.h"
#include "glints/methods.h"
#include "render/settings.h"
#include "scene/gltf_glint_material.h"
#include "scene/gltf_loader.h"
#include "scene/scene_file.h"
#include "support/process.h"

using namespace glimmer;

namespace {

// A one-triangle glTF (2 m x 2 m right triangle, UVs [0, 1]: 4 m^2 of surface per unit UV area) whose material
// carries `materialJson` (inserted into the material object) plus an optional top-level extensions object.
std::string writeModel(const std::string& dir, const std::string& name, const std::string& materialJson,
                       const std::string& topExtensions = "", const std::string& extraNodes = "", int extraNodeCount = 0) {
    std::string roots = "0";
    for (int i = 1; i <= extraNodeCount; ++i) roots += ", " + std::to_string(i);
    // positions (0,0,0) (2,0,0) (0,0,2); uvs (0,0) (1,0) (0,1); indices 0 2 1 (facing +y).
    float p[9] = {0, 0, 0, 2, 0, 0, 0, 0, 2};
    float uv[6] = {0, 0, 1, 0, 0, 1};
    unsigned short idx[3] = {0, 2, 1};
    std::string bin(reinterpret_cast<char*>(p), sizeof p);
    bin.append(reinterpret_cast<char*>(uv), sizeof uv);
    bin.append(reinterpret_cast<char*>(idx), sizeof idx);
    bin.append(2, '\0');
    std::ofstream(dir + "/" + name + ".bin", std::ios::binary) << bin;
    std::string path = dir + "/" + name + ".gltf";
    std::ofstream(path) << R"({"asset": {"version": "2.0"},)" << topExtensions << R"(
 "buffers": [{"uri": ")" << name << R"(.bin", "byteLength": )" << bin.size() << R"(}],
 "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                 {"buffer": 0, "byteOffset": 60, "byteLength": 6}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [2, 0, 2]},
               {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
               {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}],
 "images": [{"uri": "missing.png"}], "textures": [{"source": 0}],
 "materials": [{"name": "flakes")" << (materialJson.empty() ? "" : ", ") << materialJson << R"(}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
 "nodes": [{"mesh": 0})" << extraNodes << R"(], "scenes": [{"nodes": [)" << roots << R"(]}], "scene": 0})";
    return path;
}

const char* kAllKeys = R"("density": 3e5, "angularSize": 0.04, "color": [0.9, 0.5, 0.25], "colorVariation": 0.3,
 "anisotropy": 4)";

std::string loadError(const std::string& path) {
    try {
        loadGltfScene(path);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(GlintMaterialGltf, ExtensionAndExtrasLoadIntoTheSameMaterial) {
    std::string dir = test::makeTempDir("glint_material_same");
    Scene ext = loadGltfScene(writeModel(dir, "ext", std::string(R"("extensions": {"GLIMMER_materials_glint": {)") + kAllKeys + "}}"));
    Scene flat = loadGltfScene(writeModel(dir, "flat", R"("extras": {"glint_density": 3e5, "glint_angularSize": 0.04,
        "glint_color": [0.9, 0.5, 0.25], "glint_colorVariation": 0.3, "glint_anisotropy": 4, "other_tool": 1})"));
    Scene nested = loadGltfScene(writeModel(dir, "nested", std::string(R"("extras": {"GLIMMER_materials_glint": {)") + kAllKeys + "}}"));
    for (const Scene* s : {&ext, &flat, &nested}) {
        const Material& m = s->materials.at(0);
        EXPECT_TRUE(m.glinty);
        EXPECT_FLOAT_EQ(m.glint.density, 3e5f);
        EXPECT_FLOAT_EQ(m.glint.angularSize, 0.04f);
        EXPECT_FLOAT_EQ(m.glint.color.x, 0.9f);
        EXPECT_FLOAT_EQ(m.glint.color.y, 0.5f);
        EXPECT_FLOAT_EQ(m.glint.color.z, 0.25f);
        EXPECT_FLOAT_EQ(m.glint.colorVariation, 0.3f);
        EXPECT_FLOAT_EQ(m.glint.anisotropy, 4.0f);
        // 2 m x 2 m triangle over half the unit UV square: 4 m^2 of surface per unit UV area.
        EXPECT_NEAR(m.surfacePerUvArea, 4.0f, 1e-4f);
    }
}

TEST(GlintMaterialGltf, WithoutTheExtensionAMaterialIsNotGlinty) {
    std::string dir = test::makeTempDir("glint_material_plain");
    Scene s = loadGltfScene(writeModel(dir, "plain", R"("extras": {"something_else": 2})"));
    EXPECT_FALSE(s.materials.at(0).glinty);
}

// Every key alone, at a value away from its default, lands in its field (and only there).
TEST(GlintMaterialGltf, EveryKeyRoundTrips) {
    std::string dir = test::makeTempDir("glint_material_keys");
    const GlintMaterial defaults;
    int n = 0;
    for (const GlintKey& key : glintKeys()) {
        std::string k = key.name, value;
        if (k == "density") value = "123456";
        else if (k == "angularSize") value = "0.123";
        else if (k == "color") value = "[0.1, 0.2, 0.3]";
        else if (k == "colorVariation") value = "0.75";
        else if (k == "anisotropy") value = "8";
        else if (k == "densityTexture") value = R"({"index": 0})";
        else FAIL() << "new key " << k << " needs a round-trip value here";
        Scene s = loadGltfScene(writeModel(dir, "key" + std::to_string(n++),
                                           R"("extensions": {"GLIMMER_materials_glint": {")" + k + "\": " + value + "}}"));
        const Material& m = s.materials.at(0);
        EXPECT_TRUE(m.glinty) << k;
        EXPECT_FLOAT_EQ(m.glint.density, k == "density" ? 123456.0f : defaults.density) << k;
        EXPECT_FLOAT_EQ(m.glint.angularSize, k == "angularSize" ? 0.123f : defaults.angularSize) << k;
        EXPECT_FLOAT_EQ(m.glint.color.y, k == "color" ? 0.2f : defaults.color.y) << k;
        EXPECT_FLOAT_EQ(m.glint.colorVariation, k == "colorVariation" ? 0.75f : defaults.colorVariation) << k;
        EXPECT_FLOAT_EQ(m.glint.anisotropy, k == "anisotropy" ? 8.0f : defaults.anisotropy) << k;
        // The texture's image is missing (a warning): the reference resolves to "no usable texture" (-1), and a
        // texture index that does not exist is an error (below).
        EXPECT_EQ(m.glintMaskTexture, -1) << k;
    }
}

TEST(GlintMaterialGltf, BadExtensionValuesAreOneLineErrorsNamingMaterialKeyAndFile) {
    std::string dir = test::makeTempDir("glint_material_bad");
    struct Case { const char* json; const char* key; };
    for (const Case& c : {Case{R"("densty": 5)", "densty"}, Case{R"("density": "many")", "density"},
                          Case{R"("density": -1)", "density"}, Case{R"("angularSize": 2)", "angularSize"},
                          Case{R"("color": [1, 2, 0])", "color"}, Case{R"("anisotropy": 0.5)", "anisotropy"},
                          Case{R"("densityTexture": {"index": 7})", "densityTexture"}}) {
        std::string path = writeModel(dir, "bad", std::string(R"("extensions": {"GLIMMER_materials_glint": {)") + c.json + "}}");
        std::string error = loadError(path);
        EXPECT_NE(error.find(path), std::string::npos) << error;
        EXPECT_NE(error.find("material 'flakes'"), std::string::npos) << error;
        EXPECT_NE(error.find(std::string("GLIMMER_materials_glint.") + c.key), std::string::npos) << error;
        EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
}

// Extras are free-form: a bad glint key warns and keeps the default, the material stays glinty.
TEST(GlintMaterialGltf, BadExtrasWarnAndKeepTheDefault) {
    std::string dir = test::makeTempDir("glint_material_bad_extras");
    Scene s = loadGltfScene(writeModel(dir, "extras", R"("extras": {"glint_density": "lots", "glint_angularSize": 0.05})"));
    EXPECT_TRUE(s.materials.at(0).glinty);
    EXPECT_FLOAT_EQ(s.materials.at(0).glint.density, GlintMaterial{}.density);
    EXPECT_FLOAT_EQ(s.materials.at(0).glint.angularSize, 0.05f);
}

// The documented formulas (README "Glint material") against values worked by hand for alpha 0.3, 1e6 facets per
// m^2, 4 m^2 per unit UV area (4e6 per UV area), gamma 0.015.
TEST(GlintMapping, FormulasMatchHandValues) {
    Material m;
    m.alpha = 0.3f;
    m.glinty = true;
    m.glint.density = 1e6f;
    m.glint.angularSize = 0.015f;
    m.glint.anisotropy = 3.0f;
    m.glint.colorVariation = 0.5f;
    m.glint.color = {0.2f, 0.4f, 0.6f};
    m.surfacePerUvArea = 4.0f;
    ParamValues d = materialParams(findGlintMethod("deliot2023"), m, {});
    // ln(0.2 x 4e6): a fifth of the facets (the lerped angular cells and blended vertices average independent draws,
    // issue 36), the density randomization switched off (sigma 0, so no log-median offset) and the hard gate; a
    // sigma given with --set moves the log-median by sigma^2 / 2: 13.592367 - 0.5.
    EXPECT_NEAR(d["log_density"], 13.592367, 1e-4);
    EXPECT_FLOAT_EQ(d["density_randomization"], 0.0f);
    EXPECT_FLOAT_EQ(d["gate"], 1.0f);
    EXPECT_FLOAT_EQ(d["angular_grid"], 1.0f);   // lobe: glints live as long in angle as the material's
    EXPECT_NEAR(materialParams(findGlintMethod("deliot2023"), m, {{"density_randomization", 1.0f}})["log_density"],
                13.092367, 1e-4);
    EXPECT_NEAR(d["microfacet_roughness"], 0.0025, 1e-7);       // (0.015 / 0.3)^2
    EXPECT_FLOAT_EQ(d["screen_space_scale"], 1.5f);             // unmapped: default
    ParamValues z = materialParams(findGlintMethod("zirr2016"), m, {});
    EXPECT_NEAR(z["log_density"], 15.201805, 1e-4);
    EXPECT_NEAR(z["search_cone"], 0.015, 1e-7);
    ParamValues k = materialParams(findGlintMethod("kemppinen2025"), m, {});
    EXPECT_NEAR(k["density"], 4e5, 0.1);                         // 0.1 x 4e6 (issue 36)
    EXPECT_NEAR(k["micro_roughness"], 0.0106066, 1e-6);          // 0.015 / sqrt(2)
    EXPECT_FLOAT_EQ(k["glint_anisotropy"], 3.0f);
    EXPECT_FLOAT_EQ(k["color_variation"], 0.5f);
    ParamValues w = materialParams(findGlintMethod("wang2020"), m, {});
    EXPECT_NEAR(w["particles"], 4e6, 1.0);
    EXPECT_NEAR(w["gamma"], 1.7188733, 1e-5);                    // 2 x 0.015 rad in degrees
    EXPECT_FLOAT_EQ(w["roughness"], 0.3f);
    EXPECT_FLOAT_EQ(w["ndf"], 0.0f);                             // GGX (the material's)
    m.ndf = NdfType::Beckmann;
    EXPECT_FLOAT_EQ(materialParams(findGlintMethod("wang2020"), m, {})["ndf"], 1.0f);
    EXPECT_FLOAT_EQ(w["color_g"], 0.4f);
}

TEST(GlintMapping, SetOverridesTheMappedValueAndRangesClamp) {
    Material m;
    m.alpha = 0.01f;
    m.glint.angularSize = 0.2f;   // (0.2 / 0.01)^2 = 400: beyond R's range [1e-5, 1]
    ParamValues d = materialParams(findGlintMethod("deliot2023"), m, {{"log_density", 10.0f}});
    EXPECT_FLOAT_EQ(d["log_density"], 10.0f);
    EXPECT_FLOAT_EQ(d["microfacet_roughness"], 1.0f);
    RenderSettings settings;
    settings.method = "deliot2023";
    settings.apply("log_density=11");
    EXPECT_FLOAT_EQ(materialParams(findGlintMethod("deliot2023"), m, settings.methodValues("deliot2023"))["log_density"], 11.0f);
    // --list-params says which parameters are mapped and that --set overrides them.
    std::string text = describeParams();
    EXPECT_NE(text.find("per material: log_density = ln(0.2 density_per_uv) - density_randomization^2/2"), std::string::npos);
    EXPECT_NE(text.find("per material: density_randomization = 0"), std::string::npos);
    EXPECT_NE(text.find("per material: microfacet_roughness = (angular_size)^2 alpha^-2"), std::string::npos);
}

// Wang et al.'s tree is shared: it is built for the densest glinty material, the others thin it.
TEST(GlintMapping, SharedDataFollowTheDensestGlintyMaterial) {
    Material sparse, dense, plain;
    sparse.glinty = dense.glinty = true;
    sparse.glint.density = 1e4f;
    dense.glint.density = 1e6f;
    plain.glint.density = 1e9f;   // not glinty: ignored
    ParamValues shared = sharedParams(findGlintMethod("wang2020"), {sparse, plain, dense}, {});
    EXPECT_FLOAT_EQ(shared["particles"], 1e6f);
    EXPECT_FLOAT_EQ(sharedParams(findGlintMethod("deliot2023"), {sparse, dense}, {})["log_density"], std::log(0.2f * 1e4f));
}

// The lighting program compiles the enumerations every material shares as constants (methods.h uniformChoices):
// only enumerations, only when every row agrees, with that row's index; the other parameters keep reading the
// material's row.
TEST(GlintMapping, EnumerationsEveryMaterialSharesCompileAsConstants) {
    const GlintMethod& deliot = findGlintMethod("deliot2023");
    Material a, b;
    a.glinty = b.glinty = true;
    b.glint.density = 10.0f * a.glint.density;   // a different log_density (not an enumeration)
    const ParamValues soft = {{"gate", 0.0f}}, hard = {{"gate", 1.0f}};
    ParamValues same = uniformChoices(deliot, {materialParams(deliot, a, hard), materialParams(deliot, b, hard)});
    ASSERT_EQ(same.count("gate"), 1u);
    EXPECT_EQ(same["gate"], 1.0f);
    EXPECT_EQ(same.count("log_density"), 0u) << "a continuous parameter never becomes a constant";
    ParamValues mixed = uniformChoices(deliot, {materialParams(deliot, a, hard), materialParams(deliot, b, soft)});
    EXPECT_EQ(mixed.count("gate"), 0u) << "materials that disagree keep the per-material switch";
    EXPECT_EQ(mixed.count("probability"), 1u) << "the others still agree";
    EXPECT_TRUE(uniformChoices(deliot, {}).empty());
    std::string glsl = methodParamsGlsl(deliot, true, same);
    EXPECT_NE(glsl.find("#define P_GATE 1.0\n"), std::string::npos) << glsl;
    EXPECT_NE(glsl.find("#define P_LOG_DENSITY u_materialMethodParams[g_glintMaterial"), std::string::npos) << glsl;
    EXPECT_NE(methodParamsGlsl(deliot, true, mixed).find("#define P_GATE u_materialMethodParams[g_glintMaterial"),
              std::string::npos);
}

TEST(GlintLights, SpotFalloffAndRangeWindowFollowKhrLightsPunctual) {
    EXPECT_FLOAT_EQ(spotAttenuation(std::cos(0.1f), 0.2f, 0.5f), 1.0f);   // inside the inner cone
    EXPECT_FLOAT_EQ(spotAttenuation(std::cos(0.6f), 0.2f, 0.5f), 0.0f);   // outside the outer cone
    float c = 0.5f * (std::cos(0.2f) + std::cos(0.5f));                      // half-way in cos: t = 0.5
    EXPECT_NEAR(spotAttenuation(c, 0.2f, 0.5f), 0.25f, 1e-5f);
    EXPECT_FLOAT_EQ(rangeWindow(5.0f, 0.0f), 1.0f);
    EXPECT_NEAR(rangeWindow(5.0f, 10.0f), std::pow(1.0f - 0.0625f, 2.0f), 1e-6f);
    EXPECT_FLOAT_EQ(rangeWindow(11.0f, 10.0f), 0.0f);
}

TEST(GlintLights, ModelLightsAndCamerasSurviveBothRoutes) {
    std::string dir = test::makeTempDir("glint_lights");
    std::string lights = R"(
 "extensionsUsed": ["KHR_lights_punctual"],
 "extensions": {"KHR_lights_punctual": {"lights": [
   {"type": "spot", "intensity": 20, "color": [1, 0.5, 0.25], "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}},
   {"type": "directional", "intensity": 2}]}},
 "cameras": [{"type": "perspective", "name": "cam", "perspective": {"yfov": 0.7, "znear": 0.1}}],)";
    // Node 1: spot at (1, 3, 1) turned -90 degrees about x (shines down, -y); node 2: camera; the directional
    // light rides on the camera node (shines along -z).
    std::string nodes = R"(, {"translation": [1, 3, 1], "rotation": [-0.7071068, 0, 0, 0.7071068],
       "extensions": {"KHR_lights_punctual": {"light": 0}}},
     {"translation": [0, 1, 5], "camera": 0, "extensions": {"KHR_lights_punctual": {"light": 1}}})";
    std::string path = writeModel(dir, "lit", R"("extensions": {"GLIMMER_materials_glint": {}})", lights, nodes, 2);
    Scene s = loadGltfScene(path);
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_FALSE(s.fallbackLights);
    EXPECT_EQ(s.lights[0].type, LightType::Spot);
    EXPECT_NEAR(s.lights[0].vector.y, 3.0f, 1e-5f);
    EXPECT_NEAR(s.lights[0].spotDirection.y, -1.0f, 1e-5f);
    EXPECT_FLOAT_EQ(s.lights[0].innerConeAngle, 0.2f);
    EXPECT_FLOAT_EQ(s.lights[0].outerConeAngle, 0.6f);
    EXPECT_FLOAT_EQ(s.lights[0].intensity, 20.0f);
    EXPECT_EQ(s.lights[1].type, LightType::Directional);
    EXPECT_NEAR(s.lights[1].vector.z, 1.0f, 1e-5f);   // towards the light: +z
    ASSERT_GE(s.cameras.size(), 2u);
    EXPECT_EQ(s.cameras[1].name, "cam");

    // The scene-file route keeps them (translated by the model's transform) and adds its own lights.
    std::string scenePath = dir + "/lit.json";
    std::ofstream(scenePath) << R"({"models": [{"gltf": "lit.gltf", "translation": [10, 0, 0]}],
        "lights": [{"type": "point", "position": [0, 5, 0], "intensity": 3}]})";
    Scene f = loadSceneFile(scenePath);
    ASSERT_EQ(f.lights.size(), 3u);
    EXPECT_EQ(f.lights[0].type, LightType::Point);
    EXPECT_EQ(f.lights[1].type, LightType::Spot);
    EXPECT_NEAR(f.lights[1].vector.x, 11.0f, 1e-5f);
    bool haveCam = false;
    for (const Camera& c : f.cameras) haveCam |= c.name == "cam" && std::abs(c.position.x - 10.0f) < 1e-4f;
    EXPECT_TRUE(haveCam);

    // A model without lights: the glTF route uses the default key + fill (and says so), the scene-file route
    // without lights gets one default sun.
    std::string unlit = writeModel(dir, "unlit", "");
    EXPECT_TRUE(loadGltfScene(unlit).fallbackLights);
    std::ofstream(dir + "/unlit.json") << R"({"models": [{"gltf": "unlit.gltf"}]})";
    Scene u = loadSceneFile(dir + "/unlit.json");
    EXPECT_EQ(u.lights.size(), 1u);
    EXPECT_TRUE(u.fallbackLights);
    EXPECT_FALSE(u.cameras.empty());
}

TEST(GlintLights, BadSpotConesAreErrorsNamingTheLight) {
    std::string dir = test::makeTempDir("glint_lights_bad");
    std::string lights = R"( "extensions": {"KHR_lights_punctual": {"lights": [
   {"type": "spot", "spot": {"innerConeAngle": 0.7, "outerConeAngle": 0.6}}]}},)";
    std::string nodes = R"(, {"extensions": {"KHR_lights_punctual": {"light": 0}}})";
    std::string path = writeModel(dir, "badspot", "", lights, nodes, 1);
    std::string error = loadError(path);
    EXPECT_NE(error.find("KHR_lights_punctual.lights[0].spot.innerConeAngle"), std::string::npos) << error;
}

// The sample model shipped in content/: one glinty material, one plain, the model's own lights and camera.
TEST(GlintMaterialGltf, SampleModelHasOneGlintyMaterialAndItsOwnLights) {
    Scene s = loadGltfScene(std::string(GLIMMER_TEST_DIR) + "/../content/models/glint_sample.gltf");
    ASSERT_EQ(s.materials.size(), 2u);
    EXPECT_TRUE(s.materials[0].glinty);
    EXPECT_FALSE(s.materials[1].glinty);
    EXPECT_FLOAT_EQ(s.materials[0].glint.density, 4e5f);
    EXPECT_NEAR(s.materials[0].surfacePerUvArea, 16.0f, 1e-3f);
    EXPECT_EQ(s.lights.size(), 2u);
    EXPECT_FALSE(s.fallbackLights);
    EXPECT_EQ(s.lights[0].type, LightType::Spot);
    bool haveView = false;
    for (const Camera& c : s.cameras) haveView |= c.name == "view";
    EXPECT_TRUE(haveView);
}
