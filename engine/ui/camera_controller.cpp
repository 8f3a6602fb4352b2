#include "ui/camera_controller.h"

#include <algorithm>
#include <cmath>

namespace glimmer::ui {

void FlyCamera::set(const Camera& camera) { camera_ = camera; }

void FlyCamera::turn(float yawRadians, float pitchRadians) {
    glm::vec3 forward = camera_.forward();
    // Heading: the horizontal part of the view direction; for a camera looking straight down (or up) it is
    // undefined, so take the screen's up direction instead (towards it when looking down, away looking up), so the
    // first turn continues the picture instead of spinning it.
    glm::vec2 heading{forward.x, forward.z};
    if (glm::length(heading) < 1e-3f) heading = glm::vec2(camera_.up.x, camera_.up.z) * (forward.y < 0.0f ? 1.0f : -1.0f);
    float yaw = std::atan2(heading.y, heading.x) + yawRadians;
    float limit = glm::radians(89.0f);
    float pitch = std::clamp(std::asin(std::clamp(forward.y, -1.0f, 1.0f)) + pitchRadians, -limit, limit);
    glm::vec3 turned{std::cos(pitch) * std::cos(yaw), std::sin(pitch), std::cos(pitch) * std::sin(yaw)};
    camera_.target = camera_.position + turned;
    camera_.up = {0.0f, 1.0f, 0.0f};
}

void FlyCamera::move(const glm::vec3& rightUpForward) {
    glm::vec3 forward = camera_.forward();
    glm::vec3 worldUp{0.0f, 1.0f, 0.0f};
    // Screen right (from the camera's own up, which differs from world up for cameras looking straight down).
    glm::vec3 right = glm::cross(forward, camera_.up);
    if (glm::length(right) < 1e-6f) right = glm::cross(forward, worldUp);
    right = glm::length(right) > 1e-6f ? glm::normalize(right) : glm::vec3(1.0f, 0.0f, 0.0f);
    glm::vec3 delta = right * rightUpForward.x + worldUp * rightUpForward.y + forward * rightUpForward.z;
    // Move the target with the position so the view direction is kept exactly.
    camera_.position += delta;
    camera_.target += delta;
}

CameraPath::CameraPath(std::vector<Camera> cameras, float speed, float minSegmentSeconds)
    : cameras_(std::move(cameras)) {
    float t = 0.0f;
    for (size_t i = 0; i < cameras_.size(); ++i) {
        if (i > 0) t += std::max(minSegmentSeconds, glm::length(cameras_[i].position - cameras_[i - 1].position) / speed);
        times_.push_back(t);
    }
}

static glm::vec3 catmullRom(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3,
                            float t) {
    float t2 = t * t, t3 = t2 * t;
    return 0.5f * (2.0f * p1 + (p2 - p0) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 +
                   (3.0f * p1 - p0 - 3.0f * p2 + p3) * t3);
}

static glm::vec3 slerpDirection(const glm::vec3& a, const glm::vec3& b, float t) {
    float cosine = std::clamp(glm::dot(a, b), -1.0f, 1.0f);
    float angle = std::acos(cosine);
    if (angle < 1e-4f) return glm::normalize(glm::mix(a, b, t));
    float s = std::sin(angle);
    return glm::normalize((std::sin((1.0f - t) * angle) * a + std::sin(t * angle) * b) / s);
}

Camera CameraPath::at(float seconds) const {
    if (cameras_.empty()) return Camera{};
    if (cameras_.size() == 1 || seconds <= 0.0f) return cameras_.front();
    if (seconds >= duration()) return cameras_.back();
    size_t i = size_t(std::upper_bound(times_.begin(), times_.end(), seconds) - times_.begin()) - 1;
    float u = (seconds - times_[i]) / (times_[i + 1] - times_[i]);
    float eased = u * u * (3.0f - 2.0f * u);  // ease in and out of each camera so the view settles on it
    const Camera& a = cameras_[i];
    const Camera& b = cameras_[i + 1];
    const Camera& before = cameras_[i == 0 ? 0 : i - 1];
    const Camera& after = cameras_[std::min(i + 2, cameras_.size() - 1)];
    Camera c = a;
    c.name = "walkthrough";
    c.position = catmullRom(before.position, a.position, b.position, after.position, eased);
    c.target = c.position + slerpDirection(a.forward(), b.forward(), eased);
    c.up = glm::normalize(glm::mix(a.up, b.up, eased));
    c.verticalFovDegrees = glm::mix(a.verticalFovDegrees, b.verticalFovDegrees, eased);
    c.nearPlane = glm::mix(a.nearPlane, b.nearPlane, eased);
    return c;
}

}  // namespace glimmer::ui
