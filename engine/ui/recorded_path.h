// A camera path recorded in the walkthrough window (R starts and stops) and replayed there (P) or rendered
// frame by frame (`glimmer render --path FILE`). Samples are (time, position, view direction, field of view);
// between samples the position is interpolated linearly and the view direction on the unit sphere, so replay at
// any time step is deterministic. Stored as JSON:
//   {"glimmer_camera_path": 1, "scene": "atrium", "samples": [{"t": 0.0, "position": [x,y,z],
//    "forward": [x,y,z], "fov": 60.0, "near": 0.05}, ...]}
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "scene/camera.h"

namespace glimmer::ui {

class RecordedPath {
public:
    struct Sample {
        double seconds = 0.0;
        glm::vec3 position{0.0f};
        glm::vec3 forward{0.0f, 0.0f, -1.0f};
        float verticalFovDegrees = 45.0f;
        float nearPlane = 0.05f;
    };

    // Appends the camera at `seconds` (increasing times; a sample closer than minSpacing to the last is dropped).
    void add(double seconds, const Camera& camera, double minSpacing = 1.0 / 30.0);
    bool empty() const { return samples_.empty(); }
    double duration() const { return samples_.empty() ? 0.0 : samples_.back().seconds - samples_.front().seconds; }
    // The camera `seconds` after the first sample (clamped to the path).
    Camera at(double seconds) const;
    const std::vector<Sample>& samples() const { return samples_; }

    void save(const std::filesystem::path& file, const std::string& sceneName) const;
    // Throws glimmer::Error naming the file for unreadable, malformed or empty paths.
    static RecordedPath load(const std::filesystem::path& file);
    std::string sceneName;  // as loaded (informational)

private:
    std::vector<Sample> samples_;
};

}  // namespace glimmer::ui
