// Pinhole camera. Projection is reversed-Z with an infinite far plane and a [0,1] depth range
// (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE)), which keeps float depth precise at grazing angles.
#pragma once
#include <glm/glm.hpp>
#include <string>

namespace glimmer {

struct Camera {
    std::string name;
    glm::vec3 position{0.0f, 1.0f, 3.0f};
    glm::vec3 target{0.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float verticalFovDegrees = 45.0f;
    float nearPlane = 0.05f;

    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;
    glm::vec3 forward() const { return glm::normalize(target - position); }
};

// World-space ray through pixel (px, py) (pixel centres at +0.5; y measured from the bottom row as GL does).
struct Ray {
    glm::dvec3 origin;
    glm::dvec3 direction;
};
Ray cameraRay(const Camera& camera, int width, int height, double px, double py);

}  // namespace glimmer
