#include "app/walkthrough/camera_motion.h"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "app/walkthrough/overlay.h"
#include "core/clock.h"
#include "core/log.h"

namespace glimmer {

CameraMotion::CameraMotion(ui::WindowControls& controls, std::function<void(const std::string&)> showMessage)
    : controls_(controls), showMessage_(std::move(showMessage)) {}

// Walking collides with the scene's triangles (Bullet BVH, built once per scene); a scene without any flies.
void CameraMotion::prebuildCollision(const Scene& scene) {
    pendingScene_ = &scene;
    pendingCollision_ = std::async(std::launch::async, [&scene] { return std::make_unique<SceneCollision>(scene); });
}

void CameraMotion::buildCollision(const Scene& scene) {
    Stopwatch clock;
    collision_.reset();   // a scene without triangles must not walk on the previous scene's
    const bool prebuilt = pendingCollision_.valid() && pendingScene_ == &scene;
    try {
        if (pendingCollision_.valid()) {
            std::unique_ptr<SceneCollision> built = pendingCollision_.get();   // rethrows the thread's error
            if (prebuilt) collision_ = std::move(built);
        }
        if (!prebuilt) collision_ = std::make_unique<SceneCollision>(scene);
        log::info("view: collision mesh of ", collision_->triangleCount(), " triangles ",
                  prebuilt ? "ready after waiting " : "in ", twoDecimals(clock.elapsedMs()), " ms");
    } catch (const std::exception& e) {
        log::warn("view: no walking: ", e.what());
    }
}

void CameraMotion::startScene(const Scene& scene, const std::string& sceneSpec, const Camera& start,
                              std::filesystem::path pathFile, bool pathGiven, bool scripted) {
    cameras_ = scene.cameras;
    sceneName_ = scene.name;
    // A scene file named by a relative path is written absolute: the path file may be rendered from elsewhere.
    std::error_code fileError;
    sceneSpec_ = std::filesystem::is_regular_file(sceneSpec, fileError)
                     ? std::filesystem::absolute(sceneSpec, fileError).string()
                     : sceneSpec;
    pathGiven_ = pathGiven;
    buildCollision(scene);
    motion_ = std::make_unique<ui::PlayerMotion>(collision_.get());
    // Scripted input has exact times: no frame counts as a stall, so results do not depend on machine load.
    if (scripted) motion_->setStallSeconds(std::numeric_limits<double>::infinity());
    preferredMode_ = motion_->setCamera(start, ui::MoveMode::Walk);
    controls_.walking = preferredMode_ == ui::MoveMode::Walk;
    controls_.cameraNames.clear();
    for (const Camera& c : cameras_) controls_.cameraNames.push_back(c.name);
    controls_.cameraIndex = 0;
    for (size_t i = 0; i < cameras_.size(); ++i)
        if (cameras_[i].name == start.name) controls_.cameraIndex = int(i);

    pathFile_ = std::move(pathFile);
    recorded_ = ui::RecordedPath();
    std::error_code ec;
    if (std::filesystem::exists(pathFile_, ec)) {
        recorded_ = ui::RecordedPath::load(pathFile_);
        log::info("view: camera path ", pathFile_.string(), " (", recorded_.samples().size(), " samples): P plays it");
    }
    controls_.hasRecordedPath = !recorded_.empty();
}

void CameraMotion::advance(const ui::PlayerMotion::HeldSeconds& heldSeconds, double from, double to) {
    if (!(to > from)) return;
    float dt = float(to - from);
    bool keysHeld = false;
    for (ui::MoveKey key : {ui::MoveKey::Forward, ui::MoveKey::Left, ui::MoveKey::Back, ui::MoveKey::Right,
                            ui::MoveKey::Down, ui::MoveKey::Up})
        keysHeld |= heldSeconds(key, from, to) > 0.0;
    if (keysHeld) stopPathPlaying();
    if (controls_.walkthroughPlaying) {
        pathTime_ += dt;
        bool recorded = !recorded_.empty() && !controls_.recording;
        motion_->setCamera(recorded ? recorded_.at(pathTime_) : path_->at(pathTime_), ui::MoveMode::Fly);
        if (pathTime_ >= (recorded ? float(recorded_.duration()) : path_->duration())) stopPathPlaying();
    } else {
        motion_->advance(heldSeconds, from, to, controls_.moveSpeed);
    }
    if (controls_.recording) recorded_.add(to - recordStart_, motion_->camera());
}

// F: walking (collision, gravity, standing eye height) or flying (free, through everything).
void CameraMotion::toggleWalking() {
    ui::MoveMode next = motion_->mode() == ui::MoveMode::Walk ? ui::MoveMode::Fly : ui::MoveMode::Walk;
    stopPathPlaying();
    if (!motion_->setMode(next)) {
        showMessage_("no floor below the camera: flying");
        return;
    }
    preferredMode_ = next;
    controls_.walking = next == ui::MoveMode::Walk;
    if (controls_.walking && controls_.moveSpeed > 4.0f * kWalkingSpeed) controls_.moveSpeed = kWalkingSpeed;
    showMessage_(controls_.walking ? "walking (F flies)" : "flying (F walks)");
}

// P: the recorded (or --path) camera path when there is one, else the scene's cameras in order.
void CameraMotion::togglePathPlaying() {
    if (controls_.walkthroughPlaying) {
        stopPathPlaying();
        return;
    }
    if (controls_.recording) toggleRecording(0.0);   // stops: the time is not used
    pathTime_ = 0.0f;
    if (!recorded_.empty()) {
        controls_.walkthroughPlaying = true;
        showMessage_("path " + pathFile_.string() + ": " + twoDecimals(recorded_.duration()) + " s");
        return;
    }
    path_ = std::make_unique<ui::CameraPath>(cameras_, std::max(controls_.moveSpeed, 0.2f));
    if (path_->empty()) return;
    controls_.walkthroughPlaying = true;
    showMessage_("walkthrough: " + std::to_string(cameras_.size()) + " cameras, " + twoDecimals(path_->duration()) +
                 " s");
}

std::filesystem::path CameraMotion::recordingFile() const {
    std::error_code ec;
    if (pathGiven_ && !std::filesystem::exists(pathFile_, ec)) return pathFile_;
    for (int n = 1;; ++n) {
        char name[64];
        std::snprintf(name, sizeof name, "-%03d.path.json", n);
        std::filesystem::path candidate = sceneName_ + name;
        if (!std::filesystem::exists(candidate, ec)) return candidate;
    }
}

// R: starts recording the camera, or stops and saves the path as JSON (never over an existing file).
void CameraMotion::toggleRecording(double now) {
    if (!controls_.recording) {
        stopPathPlaying();
        recorded_ = ui::RecordedPath();
        recordStart_ = now;
        controls_.recording = true;
        showMessage_("recording a camera path (R stops)");
        return;
    }
    controls_.recording = false;
    controls_.hasRecordedPath = !recorded_.empty();
    try {
        std::filesystem::path file = recordingFile();
        recorded_.save(file, sceneSpec_);
        log::info("view: wrote camera path ", file.string(), " (", recorded_.samples().size(), " samples)");
        showMessage_("wrote " + file.string() + " (P plays it)");
    } catch (const std::exception& e) {
        log::error("view: ", e.what());
        showMessage_(e.what());
    }
}

void CameraMotion::stopPathPlaying() {
    if (!controls_.walkthroughPlaying) return;
    controls_.walkthroughPlaying = false;
    motion_->setCamera(motion_->camera(), preferredMode_);  // walks on from here if it stands on a floor
}

void CameraMotion::jumpToCamera(int index) {
    if (index < 0 || index >= int(cameras_.size())) return;
    stopPathPlaying();
    motion_->setCamera(cameras_[size_t(index)], preferredMode_);
    controls_.cameraIndex = index;
    controls_.walking = motion_->mode() == ui::MoveMode::Walk;
    showMessage_("camera " + cameras_[size_t(index)].name);
}

}  // namespace glimmer
