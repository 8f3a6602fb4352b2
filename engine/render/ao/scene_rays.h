// CPU ray casting against a scene's triangles in world space (Embree 3, libembree-dev): the sky-visibility bake
// (sky_visibility.h) and the tests' ray-cast AO reference use it. Alpha-masked materials count as opaque.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace glimmer::ao {

// Every instance's triangles transformed to world space (positions, indices) plus one "front" normal per
// triangle: the mean of its vertex normals, which does not depend on the winding (two-sided masonry and cloth
// need not wind consistently).
struct WorldTriangles {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    std::vector<glm::vec3> frontNormals;
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};
    size_t triangleCount() const { return indices.size() / 3; }
};
WorldTriangles worldTriangles(const Scene& scene);

struct RayHit {
    bool hit = false;
    float distance = 0.0f;
    bool backFace = false;   // the ray met the triangle from behind its front normal
};

class SceneRays {
public:
    explicit SceneRays(const WorldTriangles& triangles);
    ~SceneRays();
    SceneRays(const SceneRays&) = delete;
    SceneRays& operator=(const SceneRays&) = delete;

    // Closest hit along origin + t * direction, t in (tNear, tFar). Thread-safe.
    RayHit cast(glm::vec3 origin, glm::vec3 direction, float tNear, float tFar) const;

private:
    void* device_ = nullptr;   // RTCDevice
    void* scene_ = nullptr;    // RTCScene
    std::vector<glm::vec3> frontNormals_;
};

}  // namespace glimmer::ao
