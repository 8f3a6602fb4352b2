// Game-style camera control for the walkthrough window (WASD + mouse look) and the walkthrough path that
// interpolates through a scene's cameras in order. Pure math: no GL, no GLFW, unit-testable.
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "scene/camera.h"

namespace glimmer::ui {

// Holds a Camera and edits it. A camera that has not been moved or turned is returned bit-for-bit as it was set,
// so the window's first frame equals `glimmer render` of the same camera.
class FlyCamera {
public:
    void set(const Camera& camera);
    const Camera& camera() const { return camera_; }
    // Turns by yaw (positive: to the right) and pitch (positive: up) in radians; pitch stays within +-89 deg.
    void turn(float yawRadians, float pitchRadians);
    // Moves along the view (right, up, forward) axes; up is world up so Q/E move vertically.
    void move(const glm::vec3& rightUpForward);

private:
    Camera camera_;
};

// A path through cameras in order: positions on a uniform Catmull-Rom spline (end points
// repeated), view directions interpolated on the unit sphere, field of view linearly; each segment lasts
// its length over `speed` (at least minSegmentSeconds).
class CameraPath {
public:
    explicit CameraPath(std::vector<Camera> cameras, float speed = 1.0f, float minSegmentSeconds = 1.5f);
    float duration() const { return times_.empty() ? 0.0f : times_.back(); }
    bool empty() const { return cameras_.empty(); }
    // The camera at `seconds` from the start (clamped to the path).
    Camera at(float seconds) const;

private:
    std::vector<Camera> cameras_;
    std::vector<float> times_;   // arrival time at each camera
};

}  // namespace glimmer::ui
