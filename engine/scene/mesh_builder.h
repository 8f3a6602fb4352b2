// Building generated meshes face by face with UVs in metres along the surface (1 UV unit = 1 m), so texel
// and microfacet densities are the same everywhere. Faces never share vertices (hard edges, exact tangents).
#pragma once
#include <glm/glm.hpp>
#include <functional>
#include <vector>

#include "scene/scene.h"

namespace glimmer {

// A planar UV parametrisation: uv = (dot(p - origin, uAxis), dot(p - origin, vAxis)) with unit axes, so UV
// distances equal surface distances. Faces sharing a frame (coplanar or continuing along a wall) share UVs.
struct UvFrame {
    glm::vec3 origin{0.0f};
    glm::vec3 uAxis{1.0f, 0.0f, 0.0f};
    glm::vec3 vAxis{0.0f, 0.0f, 1.0f};
    glm::vec2 at(const glm::vec3& p) const { return {glm::dot(p - origin, uAxis), glm::dot(p - origin, vAxis)}; }
};

class MeshBuilder {
public:
    explicit MeshBuilder(std::string name) { mesh_.name = std::move(name); }

    uint32_t vertex(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& uv);
    // Triangle a, b, c; the winding is flipped if needed so it is counter-clockwise seen from the normal side.
    void triangle(uint32_t a, uint32_t b, uint32_t c);
    // A planar quad (corners in order around it) with one normal and UVs from a frame.
    void quad(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3,
              const glm::vec3& normal, const UvFrame& frame);
    // An axis-aligned box [lo, hi]; each face's UV frame is anchored at `uvOrigin` (world), with u horizontal
    // and v vertical on side faces and (x, z) on top and bottom. Faces listed in `skip` ("+y", "-x", ...) are omitted.
    void box(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& uvOrigin, const std::vector<std::string>& skip = {});
    // Vertical cylinder (no caps) standing on `base`: u = radius * phi, v = height above the base, with the
    // UV seam facing `seamDirection` (a horizontal unit vector; put it where viewers rarely look).
    void cylinder(const glm::vec3& base, float radius, float height, int segments, glm::vec3 seamDirection = {0, 0, -1});
    // Surface of revolution about the vertical axis through `base`. profile: (radius, height) points from bottom
    // to top. u = radius * phi (the local circumference, so texel density is exact along parallels),
    // v = arc length along the profile.
    void lathe(const glm::vec3& base, const std::vector<glm::vec2>& profile, int segments,
               glm::vec3 seamDirection = {0, 0, -1});
    // A regular grid over (s, t) in [0,1]^2 mapped through `surface`, with UVs from arc lengths along its rows
    // (u) and columns (v) measured on the surface itself. Normals come from the surface's partial derivatives.
    void grid(int cellsS, int cellsT, const std::function<glm::vec3(float, float)>& surface, glm::vec2 uvOffset = {0, 0});

    // Finishes the mesh: tangents from the UV gradients (generateTangents, bitangent along +dP/dv).
    MeshData finish();

private:
    MeshData mesh_;
};

}  // namespace glimmer
