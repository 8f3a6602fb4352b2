// CPU geometry of the sun's cascaded shadow maps (render/shadows/shadow_maps.h renders them): where the cascades split the
// view, the sphere that bounds each slice, the light-space texel grid every cascade snaps to, and the rule that
// decides when a cached cascade can be reused. Pure functions, tested without GL (tests/shadow_cascades_test.cpp).
//
// Stability (no shimmering when the camera moves or turns):
// - Each cascade bounds its view slice by a sphere around the eye whose radius depends only on the field of
//   view, aspect and split distance, so turning the camera changes neither the cascade's size nor its place.
// - The light's basis is a fixed rotation (no translation) and a cascade's square is centred on a multiple of
//   its texel size in that basis, so every rendering of a cascade rasterizes the scene on the same world-space
//   texel grid: a caster's edge falls on the same texels wherever the camera is.
// Caching (static geometry and light cost nothing on a still camera): a cascade is rendered over a square larger
// than its sphere (by `margin`) and reused while the part of the sphere that holds geometry stays inside it.
#pragma once
#include <glm/glm.hpp>

#include <vector>

namespace glimmer {

// Split distances (view depth, metres) of `count` cascades from `nearPlane` to `farDistance`: the practical
// split scheme (a blend, weight `lambda`, of logarithmic and uniform splits; Zhang et al. 2006, "Parallel-split
// shadow maps"). Returns count + 1 values, first nearPlane, last farDistance, strictly increasing.
std::vector<float> cascadeSplits(float nearPlane, float farDistance, int count, float lambda = 0.8f);

// The light's world-to-light rotation: rows u, v, w with w = towardLight, right-handed (u x v = w), so triangles
// that face the light are counter-clockwise in (u, v) and the G-buffer's back-face culling keeps them.
glm::mat3 lightBasis(const glm::vec3& towardLight);

struct BoundingSphere {
    glm::vec3 center{0.0f};
    float radius = 0.0f;
};

// The sphere a cascade must cover: centred on the eye, through the far corners of the view frustum at depth
// `sliceFar` (radius sliceFar sqrt(1 + tan^2(fov/2) (1 + aspect^2))), so it holds the cascade's slice of the
// view in every direction the camera may turn to. Against the smallest sphere of the slice alone (centred ahead
// of the eye) its radius is ~1.3x larger at a 60 degree field of view, but turning the camera never moves it:
// a cached cascade is re-rendered only when the camera travels, never when it turns.
BoundingSphere cascadeSphere(const glm::vec3& eye, float verticalFovDegrees, float aspect, float sliceFar);

// An axis-aligned rectangle in the light's (u, v) plane.
struct LightRect {
    glm::vec2 min{0.0f}, max{0.0f};
    bool empty() const { return !(min.x <= max.x && min.y <= max.y); }
};

// One cascade's map: a square of half-size halfExtent (metres) centred on `center` (light-space u, v), depth
// over [depthMin, depthMax] of w = dot(p, towardLight).
struct CascadeWindow {
    glm::vec2 center{0.0f};
    float halfExtent = 0.0f;
    float texelSize() const { return 2.0f * halfExtent / float(mapSize); }
    int mapSize = 1;
};

// The square a cascade's map covers for a needed region: half extent = sphere radius x (1 + margin), centre =
// the needed region's centre rounded to the nearest multiple of the texel size (halfExtent is rounded up to
// 1/64 m first so float noise in the radius never changes the grid).
CascadeWindow fitCascadeWindow(const LightRect& needed, float sphereRadius, float margin, int mapSize);

// The part of a cascade's sphere that can hold geometry: the sphere's square in (u, v) clipped to the scene's
// light-space bounds. Empty when the sphere misses the scene.
LightRect neededRect(const glm::mat3& basis, const BoundingSphere& sphere, const LightRect& sceneRect);

// True when `window` still covers `needed` with `guardTexels` texels to spare on every side (the filter's
// reach), so the cached map can be reused.
bool windowCovers(const CascadeWindow& window, const LightRect& needed, float guardTexels);

// World -> clip of a cascade: x, y in [-1, 1] over the window, depth in [0, 1] with 1 nearest the light (the
// renderer's reversed-Z convention), over the scene's depth range [depthMin, depthMax] of w.
glm::mat4 cascadeViewProjection(const glm::mat3& basis, const CascadeWindow& window, float depthMin, float depthMax);

}  // namespace glimmer
