// Where the reflection probes of a scene sit (render/probes/reflection_probes.h), and the proxy box each one's reflections
// are parallax-corrected against (Lagarde & Zanuttini 2012, "Local Image-based Lighting With Parallax-corrected
// Cubemap", SIGGRAPH talk: an influence volume that selects the probe and a box the reflected ray is intersected
// with, both axis-aligned here).
//
// Automatic placement: one probe per metallic instance (material metallic >= 0.5), the way the regular-sampling
// mode's per-object maps are placed (environment/ibl/object_environment.h): captured at the instance's centroid (moved out
// along the area-weighted mean normal for open, flat objects: meanNormal) with the instance itself left out, read by the pixels inside the instance's bounds padded by a quarter of their largest
// extent (at least 0.1), fading to the distant environment over that padding. The first `maxProbes` such instances
// in scene order get one.
// The proxy box is fitted to what the probe saw: along each of the six face axes, the median distance of the face's
// covered texels (its view depth is the distance along the axis), or the scene's bounds where at most half the face
// hit geometry (open sky); always inside the scene's bounds and containing the influence box.
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <vector>

#include "scene/scene.h"

namespace glimmer {

struct Box {
    glm::vec3 min{0.0f}, max{0.0f};
    bool contains(glm::vec3 p) const { return glm::all(glm::greaterThanEqual(p, min)) && glm::all(glm::lessThanEqual(p, max)); }
};

Box instanceBounds(const Scene& scene, const Instance& instance);   // world space
Box sceneBounds(const Scene& scene);                                 // of every instance

struct ProbePlacement {
    glm::vec3 position{0.0f};   // capture point
    Box influence;              // pixels inside read the probe
    float fade = 0.1f;          // the weight ramps from 0 at the influence faces to 1 this far inside
    int excludedInstance = -1;  // left out of the capture (the object the probe is for), -1: none
};

constexpr float kProbeMetallicThreshold = 0.5f;

std::vector<ProbePlacement> placeReflectionProbes(const Scene& scene, int maxProbes);

// Area-weighted mean of the instance's triangle normals (from the vertex normals), world space: length 0 for a closed surface,
// 1 for a flat one.
glm::vec3 meanNormal(const Scene& scene, const Instance& instance);

// `axisDistance[face]`: for each texel of cube face `face` (GL order +X, -X, +Y, -Y, +Z, -Z) the distance from the
// capture point along the face's axis to the surface seen there, or infinity for sky.
Box fitProxyBox(glm::vec3 position, const std::array<std::vector<float>, 6>& axisDistance, const Box& limits,
                const Box& mustContain);

}  // namespace glimmer
