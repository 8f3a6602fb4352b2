#include "render/probes/reflection_probe_placement.h"

#include <algorithm>
#include <cmath>

#include "environment/ibl/object_environment.h"

namespace glimmer {

Box instanceBounds(const Scene& scene, const Instance& instance) {
    const MeshData& mesh = scene.meshes.at(instance.mesh);
    Box box;
    if (mesh.positions.empty()) {
        box.min = box.max = glm::vec3(instance.transform[3]);
        return box;
    }
    box.min = glm::vec3(INFINITY);
    box.max = glm::vec3(-INFINITY);
    for (const glm::vec3& p : mesh.positions) {
        glm::vec3 w(instance.transform * glm::vec4(p, 1.0f));
        box.min = glm::min(box.min, w);
        box.max = glm::max(box.max, w);
    }
    return box;
}

Box sceneBounds(const Scene& scene) {
    Box all{glm::vec3(INFINITY), glm::vec3(-INFINITY)};
    for (const Instance& instance : scene.instances) {
        Box b = instanceBounds(scene, instance);
        all.min = glm::min(all.min, b.min);
        all.max = glm::max(all.max, b.max);
    }
    if (scene.instances.empty()) all = {glm::vec3(-1.0f), glm::vec3(1.0f)};
    return all;
}

// Area-weighted centroid of the instance's triangles, world space: the capture point. (A vertex mean, as
// ibl::instanceCentroid, leans towards duplicated seam vertices: 0.018 off on a 32 x 16 UV sphere of radius 1.)
static glm::vec3 surfaceCentroid(const Scene& scene, const Instance& instance) {
    const MeshData& mesh = scene.meshes.at(instance.mesh);
    glm::dvec3 sum(0.0);
    double area = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        glm::dvec3 a(instance.transform * glm::vec4(mesh.positions[mesh.indices[t]], 1.0f));
        glm::dvec3 b(instance.transform * glm::vec4(mesh.positions[mesh.indices[t + 1]], 1.0f));
        glm::dvec3 c(instance.transform * glm::vec4(mesh.positions[mesh.indices[t + 2]], 1.0f));
        double twiceArea = glm::length(glm::cross(b - a, c - a));
        sum += (a + b + c) * (twiceArea / 3.0);
        area += twiceArea;
    }
    return area > 0.0 ? glm::vec3(sum / area) : ibl::instanceCentroid(scene, instance);
}

glm::vec3 meanNormal(const Scene& scene, const Instance& instance) {
    const MeshData& mesh = scene.meshes.at(instance.mesh);
    glm::dvec3 sum(0.0);
    double area = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        glm::dvec3 a(instance.transform * glm::vec4(mesh.positions[mesh.indices[t]], 1.0f));
        glm::dvec3 b(instance.transform * glm::vec4(mesh.positions[mesh.indices[t + 1]], 1.0f));
        glm::dvec3 c(instance.transform * glm::vec4(mesh.positions[mesh.indices[t + 2]], 1.0f));
        double twiceArea = glm::length(glm::cross(b - a, c - a));
        // Along the shading normals (winding is not reliable on two-sided meshes), else the winding's normal.
        glm::dvec3 n = glm::cross(b - a, c - a);
        if (mesh.normals.size() == mesh.positions.size()) {
            glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(instance.transform)));
            n = glm::dvec3(normalMatrix * (mesh.normals[mesh.indices[t]] + mesh.normals[mesh.indices[t + 1]] +
                                           mesh.normals[mesh.indices[t + 2]]));
        }
        double length = glm::length(n);
        if (length > 0.0) sum += n * (twiceArea / length);
        area += twiceArea;
    }
    return area > 0.0 ? glm::vec3(sum / area) : glm::vec3(0.0f);
}

std::vector<ProbePlacement> placeReflectionProbes(const Scene& scene, int maxProbes) {
    std::vector<ProbePlacement> probes;
    // A probe leaves its own object out: with nothing else in the scene it would capture only the sky, which the
    // distant environment already gives, and its capture would cost six scene renders for nothing.
    if (scene.instances.size() < 2) return probes;
    for (size_t i = 0; i < scene.instances.size() && int(probes.size()) < maxProbes; ++i) {
        const Instance& instance = scene.instances[i];
        if (instance.material >= scene.materials.size()) continue;
        if (scene.materials[instance.material].metallic < kProbeMetallicThreshold) continue;
        Box bounds = instanceBounds(scene, instance);
        glm::vec3 extent = bounds.max - bounds.min;
        float pad = std::max(0.25f * std::max({extent.x, extent.y, extent.z}), 0.1f);
        ProbePlacement p;
        // A closed object's normals cancel (mean 0) and it is captured at its centroid; an open, flat one (a relief
        // on a wall) would be captured on its own surface, against whatever it lies on, so the point moves out
        // along the mean normal (length <= 1) by up to the padding.
        p.position = surfaceCentroid(scene, instance) + pad * meanNormal(scene, instance);
        p.influence = {bounds.min - glm::vec3(pad), bounds.max + glm::vec3(pad)};
        p.fade = pad;
        p.excludedInstance = int(i);
        probes.push_back(p);
    }
    return probes;
}

Box fitProxyBox(glm::vec3 position, const std::array<std::vector<float>, 6>& axisDistance, const Box& limits,
                const Box& mustContain) {
    Box box = limits;
    for (int face = 0; face < 6; ++face) {
        const int axis = face / 2;
        const bool positive = face % 2 == 0;
        std::vector<float> hits;
        for (float d : axisDistance[size_t(face)])
            if (std::isfinite(d) && d > 0.0f) hits.push_back(d);
        float plane = positive ? limits.max[axis] : limits.min[axis];
        if (!hits.empty() && hits.size() * 2 > axisDistance[size_t(face)].size()) {
            auto mid = hits.begin() + std::ptrdiff_t(hits.size() / 2);
            std::nth_element(hits.begin(), mid, hits.end());
            plane = position[axis] + (positive ? *mid : -*mid);
        }
        if (positive) box.max[axis] = std::clamp(plane, mustContain.max[axis], std::max(limits.max[axis], mustContain.max[axis]));
        else box.min[axis] = std::clamp(plane, std::min(limits.min[axis], mustContain.min[axis]), mustContain.min[axis]);
    }
    return box;
}

}  // namespace glimmer
