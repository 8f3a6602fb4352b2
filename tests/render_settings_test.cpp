// The common parameters named in code (render/settings.h, param::) against the table that defines them.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/error.h"
#include "render/settings.h"

namespace glimmer {
namespace {

TEST(RenderSettings, EveryKeyNamesACommonParameterAndEveryParameterHasAKey) {
    std::set<std::string> table;
    for (const CommonParam& p : commonParams()) table.insert(p.spec.name);
    std::set<std::string> keys;
    for (const CommonParamKey& key : param::kAll) {
        EXPECT_TRUE(table.count(key.name)) << "param key '" << key.name << "' names no entry of commonParams()";
        keys.insert(key.name);
    }
    for (const std::string& name : table) EXPECT_TRUE(keys.count(name)) << "no param:: key for '" << name << "'";
    // A key with no entry must fail loudly, not read a default.
    RenderSettings settings;
    EXPECT_THROW(settings.value(CommonParamKey{"exposure.typo"}), std::exception);
    EXPECT_EQ(settings.value(param::exposure), 0.0f);
    settings.apply("exposure=2");
    EXPECT_EQ(settings.value(param::exposure), 2.0f);
    EXPECT_TRUE(settings.isSet(param::exposure));
}

// Issue 37: one light's own edits (the panel's "edit light" rows) are --set keys light.<N>.<field>; anything else
// under light.<N> is a one-line usage error naming the key.
TEST(RenderSettings, LightEditKeysParseAndBadOnesNameTheKey) {
    RenderSettings settings;
    settings.apply("light.2.intensity=3");
    settings.apply("light.12.turn=-45");
    EXPECT_EQ(settings.common.at("light.2.intensity"), 3.0f);
    EXPECT_EQ(settings.common.at("light.12.turn"), -45.0f);
    EXPECT_EQ(lightEditNumber("light.12.turn"), 12);
    EXPECT_EQ(lightEditNumber("light.intensity"), 0);
    for (const char* bad : {"light.0.intensity=1", "light.65.on=1", "light.2.colour=1", "light.2.intensity=-1",
                            "light.2.turn=400", "light.x.size=1", "light.2=1", "light.2.on=maybe"}) {
        try {
            settings.apply(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const UsageError& e) {
            const std::string key = std::string(bad).substr(0, std::string(bad).find('='));
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
    clearLightEdits(settings);
    EXPECT_TRUE(settings.common.empty());
}

Scene threeLights() {
    Scene scene;
    scene.name = "three";
    Light sun;
    sun.vector = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    Light rect;
    rect.type = LightType::Rect;
    rect.vector = {0.0f, 2.0f, 0.0f};
    rect.spotDirection = {1.0f, 0.0f, 0.0f};
    rect.right = {0.0f, 0.0f, 1.0f};
    rect.width = 2.0f;
    rect.height = 0.5f;
    rect.intensity = 10.0f;
    Light sphere;
    sphere.type = LightType::Sphere;
    sphere.vector = {3.0f, 1.0f, 0.0f};
    sphere.radius = 0.25f;
    sphere.intensity = 5.0f;
    scene.lights = {sun, rect, sphere};
    return scene;
}

// Each edit changes its own light and nothing else; a switched-off light leaves the scene; the all-lights
// multipliers still apply on top; a number past the scene's lights is an error naming the key.
TEST(RenderSettings, LightEditsChangeOnlyTheirLight) {
    const Scene base = threeLights();
    RenderSettings settings;
    settings.apply("light.2.intensity=2");
    settings.apply("light.2.turn=90");
    settings.apply("light.3.size=4");
    settings.apply("light.1.size=2");
    settings.apply("light.area_intensity=3");
    Scene scene = base;
    applySceneOverrides(settings, scene);
    ASSERT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.lights[0].vector, base.lights[0].vector);
    EXPECT_NEAR(scene.lights[0].angularDiameter, 2.0f * kSunAngularDiameter, 1e-7f);
    const Light& rect = scene.lights[1];
    EXPECT_FLOAT_EQ(rect.intensity, 10.0f * 2.0f * 3.0f);
    EXPECT_EQ(rect.width, 2.0f);
    EXPECT_EQ(rect.height, 0.5f);
    EXPECT_EQ(rect.vector, base.lights[1].vector);   // turned about its own centre
    EXPECT_NEAR(rect.spotDirection.x, 0.0f, 1e-6f);  // +x turned 90 degrees about +y: -z
    EXPECT_NEAR(rect.spotDirection.z, -1.0f, 1e-6f);
    EXPECT_NEAR(rect.right.x, 1.0f, 1e-6f);
    const Light& sphere = scene.lights[2];
    EXPECT_EQ(sphere.radius, 1.0f);
    EXPECT_FLOAT_EQ(sphere.intensity, 5.0f * 3.0f);

    settings.apply("light.1.on=0");
    scene = base;
    applySceneOverrides(settings, scene);
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].type, LightType::Rect);
    EXPECT_EQ(scene.lights[1].type, LightType::Sphere);

    settings.apply("light.4.intensity=2");
    scene = base;
    try {
        applySceneOverrides(settings, scene);
        ADD_FAILURE() << "light.4 on a scene of 3 lights was accepted";
    } catch (const UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("light.4.intensity"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace glimmer
