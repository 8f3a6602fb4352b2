#include "render/shadows/shadow_projections.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace glimmer {

glm::mat4 perspectiveShadowView(const glm::vec3& eye, const glm::vec3& forward, float tanHalf, float nearPlane) {
    glm::vec3 up = std::abs(forward.y) > 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    glm::mat4 view = glm::lookAt(eye, eye + forward, up);
    float f = 1.0f / tanHalf;
    glm::mat4 projection(0.0f);
    projection[0][0] = f;
    projection[1][1] = f;
    projection[2][3] = -1.0f;
    projection[3][2] = nearPlane;
    return projection * view;
}

glm::vec3 cubeFaceDirection(int face) {
    static const glm::vec3 directions[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    return directions[std::clamp(face, 0, 5)];
}

float cubeFaceTanHalf(int mapSize, float guardTexels) {
    // A point on the face's edge (|x| = depth) lies at NDC 1 / tanHalf; the guard band is guardTexels texels
    // (2 / mapSize in NDC each) beyond it inside the map.
    float guardNdc = 2.0f * guardTexels / float(std::max(mapSize, 1));
    return 1.0f / std::max(1.0f - guardNdc, 0.5f);
}

float spotViewTanHalf(float outerConeAngle, int mapSize, float guardTexels) {
    // The cone's edge sits guardTexels inside the map's edge; the map stays square (the cone is round).
    float guardNdc = 2.0f * guardTexels / float(std::max(mapSize, 1));
    float cone = std::tan(std::clamp(outerConeAngle, 0.01f, 1.5f));
    return cone / std::max(1.0f - guardNdc, 0.5f);
}

}  // namespace glimmer
