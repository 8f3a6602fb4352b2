#include "scene/mesh_builder.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace glimmer {

uint32_t MeshBuilder::vertex(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& uv) {
    mesh_.positions.push_back(position);
    mesh_.normals.push_back(glm::normalize(normal));
    mesh_.uvs.push_back(uv);
    return uint32_t(mesh_.positions.size() - 1);
}

void MeshBuilder::triangle(uint32_t a, uint32_t b, uint32_t c) {
    glm::vec3 face = glm::cross(mesh_.positions[b] - mesh_.positions[a], mesh_.positions[c] - mesh_.positions[a]);
    glm::vec3 normal = mesh_.normals[a] + mesh_.normals[b] + mesh_.normals[c];
    if (glm::dot(face, normal) < 0.0f) std::swap(b, c);
    mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
}

void MeshBuilder::quad(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3,
                       const glm::vec3& normal, const UvFrame& frame) {
    uint32_t a = vertex(p0, normal, frame.at(p0)), b = vertex(p1, normal, frame.at(p1));
    uint32_t c = vertex(p2, normal, frame.at(p2)), d = vertex(p3, normal, frame.at(p3));
    triangle(a, b, c);
    triangle(a, c, d);
}

void MeshBuilder::box(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& uvOrigin, const std::vector<std::string>& skip) {
    auto skipped = [&](const char* face) { return std::find(skip.begin(), skip.end(), face) != skip.end(); };
    const glm::vec3 up(0, 1, 0);
    auto side = [&](const char* name, glm::vec3 normal, glm::vec3 along, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3) {
        if (skipped(name)) return;
        quad(p0, p1, p2, p3, normal, {uvOrigin, along, up});
    };
    side("+x", {1, 0, 0}, {0, 0, -1}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z});
    side("-x", {-1, 0, 0}, {0, 0, 1}, {lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z});
    side("+z", {0, 0, 1}, {1, 0, 0}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
    side("-z", {0, 0, -1}, {-1, 0, 0}, {lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z});
    UvFrame horizontal{uvOrigin, {1, 0, 0}, {0, 0, 1}};
    if (!skipped("+y")) quad({lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}, {0, 1, 0}, horizontal);
    if (!skipped("-y")) quad({lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}, {0, -1, 0}, horizontal);
}

void MeshBuilder::cylinder(const glm::vec3& base, float radius, float height, int segments, glm::vec3 seamDirection) {
    lathe(base, {{radius, 0.0f}, {radius, height}}, segments, seamDirection);
}

void MeshBuilder::lathe(const glm::vec3& base, const std::vector<glm::vec2>& profile, int segments, glm::vec3 seamDirection) {
    const float twoPi = glm::two_pi<float>();
    const float phi0 = std::atan2(seamDirection.x, -seamDirection.z);  // the seam (phi = 0) faces seamDirection
    std::vector<float> arc(profile.size(), 0.0f);
    for (size_t i = 1; i < profile.size(); ++i) arc[i] = arc[i - 1] + glm::length(profile[i] - profile[i - 1]);
    uint32_t first = uint32_t(mesh_.positions.size());
    for (size_t i = 0; i < profile.size(); ++i) {
        // Profile tangent gives the normal in the meridian plane: rotate (dr, dy) by -90 degrees.
        glm::vec2 d = profile[std::min(i + 1, profile.size() - 1)] - profile[i == 0 ? 0 : i - 1];
        glm::vec2 meridianNormal = glm::normalize(glm::vec2(d.y, -d.x));
        for (int s = 0; s <= segments; ++s) {
            float phi = twoPi * float(s) / float(segments);
            glm::vec3 radial(std::sin(phi + phi0), 0.0f, -std::cos(phi + phi0));
            glm::vec3 p = base + radial * profile[i].x + glm::vec3(0, profile[i].y, 0);
            glm::vec3 n = radial * meridianNormal.x + glm::vec3(0, meridianNormal.y, 0);
            vertex(p, n, {profile[i].x * phi, arc[i]});
        }
    }
    uint32_t row = uint32_t(segments + 1);
    for (size_t i = 0; i + 1 < profile.size(); ++i)
        for (int s = 0; s < segments; ++s) {
            uint32_t a = first + uint32_t(i) * row + uint32_t(s), b = a + 1, c = a + row, d = c + 1;
            triangle(a, b, d);
            triangle(a, d, c);
        }
}

void MeshBuilder::grid(int cellsS, int cellsT, const std::function<glm::vec3(float, float)>& surface, glm::vec2 uvOffset) {
    uint32_t first = uint32_t(mesh_.positions.size());
    int ns = cellsS + 1, nt = cellsT + 1;
    std::vector<glm::vec3> p(size_t(ns) * nt);
    for (int j = 0; j < nt; ++j)
        for (int i = 0; i < ns; ++i) p[size_t(j) * ns + i] = surface(float(i) / cellsS, float(j) / cellsT);
    // u: arc length along each row from its first vertex; v: arc length along each column from its first
    // vertex. Both are measured on the surface, so lengths along the grid lines are exact and areas are exact
    // where the grid lines cross at right angles.
    std::vector<float> v(size_t(ns), 0.0f);
    for (int j = 0; j < nt; ++j) {
        float u = 0.0f;
        for (int i = 0; i < ns; ++i) {
            if (i > 0) u += glm::length(p[size_t(j) * ns + i] - p[size_t(j) * ns + i - 1]);
            if (j > 0) v[size_t(i)] += glm::length(p[size_t(j) * ns + i] - p[size_t(j - 1) * ns + i]);
            glm::vec3 ds = p[size_t(j) * ns + std::min(i + 1, ns - 1)] - p[size_t(j) * ns + std::max(i - 1, 0)];
            glm::vec3 dt = p[size_t(std::min(j + 1, nt - 1)) * ns + i] - p[size_t(std::max(j - 1, 0)) * ns + i];
            glm::vec3 n = glm::cross(dt, ds);
            if (glm::dot(n, n) < 1e-20f) n = glm::vec3(0, 1, 0);
            vertex(p[size_t(j) * ns + i], n, glm::vec2(u, v[size_t(i)]) + uvOffset);
        }
    }
    for (int j = 0; j < cellsT; ++j)
        for (int i = 0; i < cellsS; ++i) {
            uint32_t a = first + uint32_t(j * ns + i), b = a + 1, c = a + uint32_t(ns), d = c + 1;
            triangle(a, b, d);
            triangle(a, d, c);
        }
}

MeshData MeshBuilder::finish() {
    generateTangents(mesh_, BitangentConvention::UvUp);
    return std::move(mesh_);
}

}  // namespace glimmer
