// The texture-lookup UV transform of KHR_texture_transform, shared by the glTF loader, scene files and
// generated scenes: uv' = T(offset) * R(rotation) * S(scale) * uv, with the extension's rotation matrix
// [cos sin; -sin cos] (rotation in radians, counter-clockwise in UV space with v pointing down).
#pragma once
#include <glm/glm.hpp>

#include <cmath>

namespace glimmer {

inline glm::mat3 uvTransformMatrix(glm::vec2 offset, float rotation, glm::vec2 scale) {
    float c = std::cos(rotation), s = std::sin(rotation);
    glm::mat3 m(1.0f);   // glm is column-major: m[column][row]
    m[0][0] = scale.x * c;  m[1][0] = scale.y * s;  m[2][0] = offset.x;
    m[0][1] = -scale.x * s; m[1][1] = scale.y * c;  m[2][1] = offset.y;
    return m;
}

}  // namespace glimmer
