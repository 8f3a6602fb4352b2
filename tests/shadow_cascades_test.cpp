// The CPU geometry of the shadow maps (render/shadows/shadow_cascades.h, render/shadows/shadow_projections.h): split distances,
// cascade spheres that hold their view slice wherever the camera turns, texel snapping, the
// cache rule, and the projections' ranges. No GL.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

#include "render/shadows/shadow_cascades.h"
#include "render/shadows/shadow_projections.h"

namespace glimmer {
namespace {

TEST(ShadowCascades, SplitsIncreaseFromNearToFar) {
    for (int count : {1, 2, 3, 4}) {
        std::vector<float> splits = cascadeSplits(0.05f, 40.0f, count);
        ASSERT_EQ(splits.size(), size_t(count) + 1);
        EXPECT_FLOAT_EQ(splits.front(), 0.05f);
        EXPECT_FLOAT_EQ(splits.back(), 40.0f);
        for (size_t i = 1; i < splits.size(); ++i) EXPECT_GT(splits[i], splits[i - 1]);
    }
    // lambda 1: logarithmic (equal ratios), lambda 0: uniform (equal steps).
    std::vector<float> log = cascadeSplits(1.0f, 64.0f, 3, 1.0f), uni = cascadeSplits(1.0f, 64.0f, 3, 0.0f);
    EXPECT_NEAR(log[1], 4.0f, 1e-4f);
    EXPECT_NEAR(log[2], 16.0f, 1e-3f);
    EXPECT_NEAR(uni[1], 22.0f, 1e-4f);
    EXPECT_NEAR(uni[2], 43.0f, 1e-4f);
}

TEST(ShadowCascades, LightBasisIsARightHandedRotationWithTheLightAsW) {
    for (glm::vec3 toward : {glm::vec3(0.35f, 0.8f, 0.45f), glm::vec3(0, 1, 0), glm::vec3(1, 0.01f, 0), glm::vec3(0, -1, 0)}) {
        glm::mat3 b = lightBasis(toward);
        glm::vec3 u = glm::vec3(b[0][0], b[1][0], b[2][0]), v = glm::vec3(b[0][1], b[1][1], b[2][1]),
                  w = glm::vec3(b[0][2], b[1][2], b[2][2]);
        EXPECT_NEAR(glm::length(glm::cross(u, v) - w), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::length(w - glm::normalize(toward)), 0.0f, 1e-5f);
        EXPECT_NEAR(glm::determinant(b), 1.0f, 1e-5f);
    }
}

// The 8 corners of a view-frustum slice.
std::vector<glm::vec3> sliceCorners(glm::vec3 eye, glm::vec3 forward, float fov, float aspect, float n, float f) {
    glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    glm::vec3 up = glm::cross(right, forward);
    float t = std::tan(glm::radians(fov) * 0.5f);
    std::vector<glm::vec3> corners;
    for (float d : {n, f})
        for (float sx : {-1.0f, 1.0f})
            for (float sy : {-1.0f, 1.0f}) corners.push_back(eye + forward * d + right * (sx * d * t * aspect) + up * (sy * d * t));
    return corners;
}

TEST(ShadowCascades, CascadeSphereHoldsItsSliceWhereverTheCameraTurns) {
    const glm::vec3 eye(3.0f, 1.7f, -2.0f);
    for (float aspect : {1.0f, 16.0f / 9.0f})
        for (float fov : {30.0f, 60.0f, 90.0f}) {
            std::vector<float> splits = cascadeSplits(0.05f, 40.0f, 3);
            for (size_t k = 0; k + 1 < splits.size(); ++k) {
                BoundingSphere s = cascadeSphere(eye, fov, aspect, splits[k + 1]);
                float farthest = 0.0f;
                for (float yaw = 0.0f; yaw < 360.0f; yaw += 37.0f)
                    for (float pitch : {-80.0f, -20.0f, 0.0f, 45.0f}) {
                        float p = glm::radians(pitch), y = glm::radians(yaw);
                        glm::vec3 forward(std::cos(p) * std::cos(y), std::sin(p), std::cos(p) * std::sin(y));
                        for (const glm::vec3& c : sliceCorners(eye, forward, fov, aspect, splits[k], splits[k + 1])) {
                            EXPECT_LE(glm::distance(c, s.center), s.radius * (1.0f + 1e-5f));
                            farthest = std::max(farthest, glm::distance(c, s.center));
                        }
                    }
                EXPECT_NEAR(farthest, s.radius, 1e-4f * s.radius) << "tight: the far corners lie on the sphere";
            }
        }
}

TEST(ShadowCascades, WindowsSnapToOneWorldTexelGrid) {
    const int size = 1024;
    const float radius = 3.7f;
    LightRect needed{{-1.0f, 2.0f}, {6.4f, 9.4f}};
    CascadeWindow a = fitCascadeWindow(needed, radius, 0.25f, size);
    float texel = a.texelSize();
    EXPECT_GE(a.halfExtent, radius * 1.25f);
    EXPECT_NEAR(a.center.x / texel, std::round(a.center.x / texel), 1e-3f);
    EXPECT_NEAR(a.center.y / texel, std::round(a.center.y / texel), 1e-3f);
    // The needed region moved by a third of a texel, then by 10.4 texels: the same half extent, and centres that
    // differ by whole texels, so both maps sample the world on the same grid.
    for (float shift : {texel / 3.0f, 10.4f * texel}) {
        LightRect moved{needed.min + shift, needed.max + shift};
        CascadeWindow b = fitCascadeWindow(moved, radius, 0.25f, size);
        EXPECT_EQ(b.halfExtent, a.halfExtent);
        glm::vec2 steps = (b.center - a.center) / texel;
        EXPECT_NEAR(steps.x, std::round(steps.x), 1e-3f);
        EXPECT_NEAR(steps.y, std::round(steps.y), 1e-3f);
    }
}

TEST(ShadowCascades, ACachedWindowCoversSmallMovesButNotLargeOnes) {
    const float radius = 4.0f;
    LightRect needed{{-radius, -radius}, {radius, radius}};
    CascadeWindow window = fitCascadeWindow(needed, radius, 0.25f, 2048);
    const float guard = 3.5f;
    EXPECT_TRUE(windowCovers(window, needed, guard));
    auto moved = [&](glm::vec2 d) { return LightRect{needed.min + d, needed.max + d}; };
    // The margin is 1 m; the guard 3.5 texels of 4.9 mm.
    EXPECT_TRUE(windowCovers(window, moved({0.9f, -0.9f}), guard));
    EXPECT_FALSE(windowCovers(window, moved({1.01f, 0.0f}), guard));
    EXPECT_FALSE(windowCovers(window, moved({0.0f, -1.01f}), guard));
    EXPECT_TRUE(windowCovers(window, LightRect{{5.0f, 5.0f}, {4.0f, 4.0f}}, guard)) << "an empty region needs nothing";
}

TEST(ShadowCascades, CascadeProjectionMapsTheWindowToClipSpace) {
    glm::mat3 basis = lightBasis({0.35f, 0.8f, 0.45f});
    CascadeWindow window;
    window.center = {2.0f, -1.0f};
    window.halfExtent = 5.0f;
    window.mapSize = 1024;
    glm::mat4 m = cascadeViewProjection(basis, window, -3.0f, 17.0f);
    glm::mat3 toWorld = glm::transpose(basis);
    auto clip = [&](glm::vec3 light) { return glm::vec3(m * glm::vec4(toWorld * light, 1.0f)); };
    glm::vec3 c0 = clip({-3.0f, -6.0f, -3.0f}), c1 = clip({7.0f, 4.0f, 17.0f});
    EXPECT_NEAR(c0.x, -1.0f, 1e-5f);
    EXPECT_NEAR(c0.y, -1.0f, 1e-5f);
    EXPECT_NEAR(c0.z, 0.0f, 1e-5f);
    EXPECT_NEAR(c1.x, 1.0f, 1e-5f);
    EXPECT_NEAR(c1.y, 1.0f, 1e-5f);
    EXPECT_NEAR(c1.z, 1.0f, 1e-5f) << "depth 1 nearest the light (reversed Z)";
}

TEST(ShadowCascades, CubeFacesCoverEveryDirectionWithTheFilterGuard) {
    const int size = 256;
    const float guard = 3.5f;
    float tanHalf = cubeFaceTanHalf(size, guard);
    EXPECT_GT(tanHalf, 1.0f);
    const glm::vec3 light(1.0f, 2.0f, 3.0f);
    // Directions on a face's edge (45 degrees off its axis): inside the map by the guard band.
    for (int face = 0; face < 6; ++face) {
        glm::mat4 m = perspectiveShadowView(light, cubeFaceDirection(face), tanHalf, 0.05f);
        glm::vec3 axis = cubeFaceDirection(face);
        glm::vec3 side = std::abs(axis.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        glm::vec3 other = glm::cross(axis, side);
        for (glm::vec3 edge : {axis + side, axis - side, axis + other, axis - other, axis + side + other}) {
            glm::vec4 c = m * glm::vec4(light + 2.0f * edge, 1.0f);
            glm::vec2 ndc = glm::vec2(c) / c.w;
            float limit = 1.0f - 2.0f * guard / float(size);
            EXPECT_LE(std::abs(ndc.x), limit + 1e-4f) << "face " << face;
            EXPECT_LE(std::abs(ndc.y), limit + 1e-4f) << "face " << face;
            EXPECT_GT(c.z / c.w, 0.0f);
            EXPECT_LT(c.z / c.w, 1.0f);
        }
    }
}

}  // namespace
}  // namespace glimmer
