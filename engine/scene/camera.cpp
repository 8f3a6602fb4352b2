#include "scene/camera.h"

#include <glm/gtc/matrix_transform.hpp>

namespace glimmer {

glm::mat4 Camera::view() const { return glm::lookAt(position, target, up); }

glm::mat4 Camera::projection(float aspect) const {
    // Reversed-Z infinite perspective: depth = near / z_view_distance, 1 at the near plane, 0 at infinity.
    float f = 1.0f / std::tan(glm::radians(verticalFovDegrees) * 0.5f);
    glm::mat4 p(0.0f);
    p[0][0] = f / aspect;
    p[1][1] = f;
    p[2][3] = -1.0f;
    p[3][2] = nearPlane;
    return p;
}

Ray cameraRay(const Camera& camera, int width, int height, double px, double py) {
    glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - glm::dvec3(camera.position));
    glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(camera.up)));
    glm::dvec3 up = glm::cross(right, forward);
    double tanHalf = std::tan(glm::radians(double(camera.verticalFovDegrees)) * 0.5);
    double aspect = double(width) / double(height);
    double ndcX = 2.0 * px / width - 1.0;
    double ndcY = 2.0 * py / height - 1.0;
    glm::dvec3 direction = forward + right * (ndcX * tanHalf * aspect) + up * (ndcY * tanHalf);
    return {glm::dvec3(camera.position), glm::normalize(direction)};
}

}  // namespace glimmer
