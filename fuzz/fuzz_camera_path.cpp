// libFuzzer target: a camera path (ui/recorded_path.cpp) as render --path reads it, then the cameras it gives
// at the times and frame count render --path would use (app/render_path.cpp): no undefined conversion, no
// non-finite camera from a path that loaded.
#include <cmath>
#include <cstdlib>

#include "core/error.h"
#include "fuzz_support.h"
#include "ui/recorded_path.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    glimmer::fuzz::quietLogs();
    try {
        glimmer::ui::RecordedPath path = glimmer::ui::RecordedPath::load(glimmer::fuzz::writeInput(data, size, ".json"));
        const double fps = 30.0;
        const double frames = std::floor(path.duration() * fps + 1e-9) + 1.0;   // as render --path, in double
        if (!(frames >= 1.0 && frames <= 3e7)) std::abort();                     // 1e6 s x 30 fps at most
        for (double t : {0.0, path.duration() * 0.37, path.duration(), path.duration() + 1.0}) {
            glimmer::Camera c = path.at(t);
            glm::vec3 f = c.forward();
            if (!std::isfinite(f.x) || !std::isfinite(f.y) || !std::isfinite(f.z) || !(c.nearPlane > 0.0f)) std::abort();
        }
    } catch (const glimmer::Error&) {
    }
    return 0;
}
