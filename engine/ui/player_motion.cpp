#include "ui/player_motion.h"

#include <algorithm>
#include <cmath>

namespace glimmer::ui {

static constexpr float kStandingTolerance = 0.2f;  // a camera within 20 cm of standing height walks

MoveMode PlayerMotion::setCamera(const Camera& camera, MoveMode preferred) {
    fly_.set(camera);
    mode_ = MoveMode::Fly;
    if (preferred == MoveMode::Walk && collision_ && collision_->standingAt(camera.position, kStandingTolerance)) {
        collision_->placeEye(camera.position);
        mode_ = MoveMode::Walk;
    }
    return mode_;
}

bool PlayerMotion::setMode(MoveMode mode) {
    if (mode == mode_) return true;
    if (mode == MoveMode::Walk) {
        // Without a floor somewhere below (a model seen from outside), walking would fall forever.
        if (!collision_ || !collision_->floorBelow(fly_.camera().position, kFloorSearchMetres)) return false;
        collision_->placeEye(fly_.camera().position);  // falls from here onto the floor below
    }
    mode_ = mode;
    return true;
}

bool PlayerMotion::advance(const HeldSeconds& heldSeconds, double from, double to, float speed) {
    if (!(to > from)) return false;
    if (to - from > stallSeconds_) from = to - kMaxStepSeconds;
    int steps = std::max(1, int(std::ceil((to - from) / kMaxStepSeconds - 1e-9)));
    double stepSeconds = (to - from) / steps;
    bool moved = false;
    for (int i = 0; i < steps; ++i) {
        double a = from + stepSeconds * i, b = a + stepSeconds;
        auto held = [&](MoveKey key) { return float(heldSeconds(key, a, b)); };
        // Seconds moved along each axis in this step; a diagonal moves no faster than a straight line.
        glm::vec3 seconds{held(MoveKey::Right) - held(MoveKey::Left), held(MoveKey::Up) - held(MoveKey::Down),
                          held(MoveKey::Forward) - held(MoveKey::Back)};
        float fast = 1.0f + (kFastFactor - 1.0f) * held(MoveKey::Fast) / float(stepSeconds);
        if (mode_ == MoveMode::Fly) {
            float length = glm::length(seconds);
            if (length > float(stepSeconds)) seconds *= float(stepSeconds) / length;
            if (length > 0.0f) {
                fly_.move(seconds * speed * fast);
                moved = true;
            }
            continue;
        }
        // Walking: forward is the view direction's heading; up/down keys do nothing (gravity decides).
        const Camera& c = fly_.camera();
        glm::vec3 forward = c.forward();
        glm::vec3 heading{forward.x, 0.0f, forward.z};
        if (glm::length(heading) < 1e-4f) heading = glm::vec3(c.up.x, 0.0f, c.up.z) * (forward.y < 0.0f ? 1.0f : -1.0f);
        heading = glm::length(heading) > 1e-6f ? glm::normalize(heading) : glm::vec3(0.0f, 0.0f, -1.0f);
        glm::vec3 right = glm::normalize(glm::cross(heading, glm::vec3(0.0f, 1.0f, 0.0f)));
        glm::vec2 flat{seconds.x, seconds.z};
        float length = glm::length(flat);
        if (length > float(stepSeconds)) flat *= float(stepSeconds) / length;
        glm::vec3 velocity = (right * flat.x + heading * flat.y) * (speed * fast / float(stepSeconds));
        collision_->step(velocity, float(stepSeconds));
        glm::vec3 eye = collision_->eye();
        // Standing still, Bullet's character settles by a few micrometres: keep the camera exact until it moves.
        if (glm::length(eye - c.position) > 1e-4f) {
            Camera moved_ = c;
            moved_.target = eye + (c.target - c.position);
            moved_.position = eye;
            fly_.set(moved_);
            moved = true;
        }
    }
    return moved;
}

}  // namespace glimmer::ui
