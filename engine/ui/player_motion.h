// The walkthrough camera's motion over wall time: flying (free, no collision) or walking (a standing character
// that collides with the scene: scene/character_collision.h). Movement is speed x the seconds each key was held
// (ui/key_holds.h), integrated in steps of at most kMaxStepSeconds so collision and gravity see small moves;
// a frame interval longer than kStallSeconds (a window drag, a shader rebuild) counts only its last step, so a
// stall never teleports the camera.
#pragma once
#include <functional>

#include "scene/camera.h"
#include "scene/character_collision.h"
#include "ui/camera_controller.h"

namespace glimmer::ui {

constexpr double kMaxStepSeconds = 0.1;
constexpr double kStallSeconds = 1.0;
constexpr float kFastFactor = 4.0f;   // while the fast key (Shift) is held
constexpr float kFloorSearchMetres = 1000.0f;

enum class MoveMode { Fly, Walk };
enum class MoveKey { Forward, Back, Left, Right, Up, Down, Fast };

class PlayerMotion {
public:
    // collision may be null (then only flying is possible).
    explicit PlayerMotion(SceneCollision* collision) : collision_(collision) {}

    // Jumps to a camera. Walking continues there only when the camera stands on a floor (its eye at standing
    // height above one), else the motion switches to flying; returns the mode in effect.
    MoveMode setCamera(const Camera& camera, MoveMode preferred);
    // Walking needs collision and a floor below the camera; returns false (and stays flying) without them.
    bool setMode(MoveMode mode);
    MoveMode mode() const { return mode_; }
    const Camera& camera() const { return fly_.camera(); }
    void turn(float yawRadians, float pitchRadians) { fly_.turn(yawRadians, pitchRadians); }

    // Advances over the wall-time interval [from, to]; heldSeconds(key, a, b) says how long a key was held in
    // [a, b]. Returns true when the camera moved.
    using HeldSeconds = std::function<double(MoveKey, double, double)>;
    bool advance(const HeldSeconds& heldSeconds, double from, double to, float speed);
    // Frames longer than this count as a stall (default kStallSeconds).
    void setStallSeconds(double seconds) { stallSeconds_ = seconds; }

private:
    SceneCollision* collision_;
    FlyCamera fly_;
    MoveMode mode_ = MoveMode::Fly;
    double stallSeconds_ = kStallSeconds;
};

}  // namespace glimmer::ui
