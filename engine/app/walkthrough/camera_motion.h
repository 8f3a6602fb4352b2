// Where the window's camera is: walking (collision with the scene, gravity) or flying, jumps to the scene's
// cameras, and camera paths: playing the recorded path or a tour of the scene's cameras (P), recording one (R).
#pragma once
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/character_collision.h"
#include "scene/scene.h"
#include "ui/camera_controller.h"
#include "ui/player_motion.h"
#include "ui/recorded_path.h"
#include "ui/settings_panel.h"

namespace glimmer {

constexpr float kWalkingSpeed = 1.8f;  // m/s, a brisk walk

class CameraMotion {
public:
    // `controls`: the panel's state this keeps current (walking, speed, camera list, path playing / recording).
    CameraMotion(ui::WindowControls& controls, std::function<void(const std::string&)> showMessage);

    // A scene starts at `start`: collision of `scene`'s triangles (walking needs them), its cameras, and the camera
    // path in `pathFile` when that exists (P plays it). R never overwrites a file: it saves to `pathFile` only when
    // that was given (--path) and does not exist yet, else to the working folder's next free
    // `<scene>-NNN.path.json` (a shipped path such as content/atrium.path.json feeds P, --walkthrough and the
    // benchmark). `sceneSpec`: the scene as named on the command line, written into the path file so that
    // `render --path` finds it. `scripted`: input with exact times, no frame is a stall.
    void startScene(const Scene& scene, const std::string& sceneSpec, const Camera& start,
                    std::filesystem::path pathFile, bool pathGiven, bool scripted);
    // Starts building `scene`'s collision on another thread (the Bullet BVH is CPU work, about 0.1 s for the
    // atrium): the window's start uploads the scene to the GPU and builds its shaders meanwhile, and startScene
    // with the same scene, unchanged until then, takes the result.
    void prebuildCollision(const Scene& scene);

    const Camera& camera() const { return motion_->camera(); }
    ui::MoveMode mode() const { return motion_->mode(); }
    // What F chose; cameras that do not stand on a floor fly.
    ui::MoveMode preferredMode() const { return preferredMode_; }
    void turn(float yawRadians, float pitchRadians) { motion_->turn(yawRadians, pitchRadians); }

    // Motion over [from, to]: the camera path while it plays, else the held movement keys (and recording).
    void advance(const ui::PlayerMotion::HeldSeconds& heldSeconds, double from, double to);

    void toggleWalking();                    // F
    void togglePathPlaying();                // P
    void toggleRecording(double now);        // R; `now` on the frame clock
    void stopPathPlaying();
    void jumpToCamera(int index);            // keys 1..9 and the panel

private:
    void buildCollision(const Scene& scene);
    std::filesystem::path recordingFile() const;   // where R saves now (a file that does not exist)

    ui::WindowControls& controls_;
    std::function<void(const std::string&)> showMessage_;
    std::vector<Camera> cameras_;
    std::string sceneName_;
    std::unique_ptr<SceneCollision> collision_;  // null for a scene without triangles
    std::future<std::unique_ptr<SceneCollision>> pendingCollision_;   // prebuildCollision's, for pendingScene_
    const Scene* pendingScene_ = nullptr;
    std::unique_ptr<ui::PlayerMotion> motion_;
    ui::MoveMode preferredMode_ = ui::MoveMode::Walk;
    std::unique_ptr<ui::CameraPath> path_;       // the tour of the scene's cameras
    ui::RecordedPath recorded_;
    std::filesystem::path pathFile_;
    bool pathGiven_ = false;
    std::string sceneSpec_;     // written into recorded paths
    double recordStart_ = 0.0;
    float pathTime_ = 0.0f;
};

}  // namespace glimmer
