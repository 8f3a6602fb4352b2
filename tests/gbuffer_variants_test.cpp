// The G-buffer program leaves out the lookups of texture slots no material of the scene uses (occlusion, glint
// mask, clear coat: GBUFFER_EXTRA_TEXTURES, render/frame/gbuffer_pass.h): a renderer that first draws a scene
// without such a texture and then one with an occlusion texture must shade the occlusion exactly as a renderer that
// only ever saw the textured scene, and going back must give the untextured image again.
#include <gtest/gtest.h>

#include <memory>

#include "core/files.h"
#include "platform/context.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "scene/builtin_scenes.h"
#include "scene/mesh_builder.h"
#include "support/test_needs.h"

GLIMMER_SUITE_NEEDS(GBufferVariants, GlContext);

namespace glimmer {
namespace {

// A lit grey plane seen from above, no environment.
Scene planeScene() {
    Scene scene;
    scene.name = "gbuffer-variants";
    scene.environment = "none";
    scene.skyColor = glm::vec3(0.2f);
    scene.meshes.push_back(makeGroundPlane(2.0f, 2, 0.0f));
    Material grey;
    grey.baseColor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
    grey.alpha = 0.5f;
    scene.materials = {grey};
    scene.instances = {{0, 0, glm::mat4(1.0f)}};
    Light sun;
    sun.type = LightType::Directional;
    sun.vector = {0.3f, 1.0f, 0.2f};
    sun.intensity = 2.0f;
    scene.lights = {sun};
    Camera camera;
    camera.name = "top";
    camera.position = {0.0f, 3.0f, 0.0f};
    camera.target = {0.0f, 0.0f, 0.0f};
    camera.up = {0.0f, 0.0f, -1.0f};
    scene.cameras = {camera};
    return scene;
}

// The same plane with an occlusion texture: dark (0.2) and white texels in an 8 x 8 checker.
Scene occludedPlaneScene() {
    Scene scene = planeScene();
    TextureData checker;
    checker.name = "occlusion checker";
    checker.width = checker.height = 8;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            uint8_t v = (x + y) % 2 ? 255 : 51;
            checker.rgba.insert(checker.rgba.end(), {v, v, v, 255});
        }
    scene.textures = {checker};
    scene.materials[0].occlusionTexture = 0;
    return scene;
}

std::vector<float> renderWith(Renderer& renderer, const Scene& scene) {
    GpuScene gpu(scene);
    renderer.renderView(scene, gpu, scene.cameras.front(), 64, 64);
    return renderer.readHdr();
}

TEST(GBufferVariants, ProgramFollowsTheScenesTextureSlots) {
    std::unique_ptr<GLContext> context = createHeadlessContext(Backend::Egl);
    const Scene plain = planeScene(), occluded = occludedPlaneScene();
    std::vector<float> freshPlain, freshOccluded, first, textured, again;
    {
        Renderer fresh(defaultShaderDir(), RenderSettings{});
        freshPlain = renderWith(fresh, plain);
    }
    {
        Renderer fresh(defaultShaderDir(), RenderSettings{});
        freshOccluded = renderWith(fresh, occluded);
    }
    {
        Renderer renderer(defaultShaderDir(), RenderSettings{});
        first = renderWith(renderer, plain);
        textured = renderWith(renderer, occluded);
        again = renderWith(renderer, plain);
    }
    EXPECT_TRUE(first == freshPlain);
    EXPECT_FALSE(freshOccluded == freshPlain) << "the occlusion texture changes nothing (the test proves nothing)";
    EXPECT_TRUE(textured == freshOccluded) << "an occlusion texture that appeared after the first frame is not read";
    EXPECT_TRUE(again == freshPlain) << "the texture's removal did not restore the untextured image";
}

}  // namespace
}  // namespace glimmer
