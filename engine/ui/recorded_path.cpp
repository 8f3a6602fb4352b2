#include "ui/recorded_path.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/error.h"
#include "core/files.h"
#include "scene/scene_limits.h"

namespace glimmer::ui {

void RecordedPath::add(double seconds, const Camera& camera, double minSpacing) {
    if (!samples_.empty() && seconds - samples_.back().seconds < minSpacing) return;
    samples_.push_back({seconds, camera.position, camera.forward(), camera.verticalFovDegrees, camera.nearPlane});
}

static glm::vec3 slerpUnit(const glm::vec3& a, const glm::vec3& b, float t) {
    float cosine = std::clamp(glm::dot(a, b), -1.0f, 1.0f);
    float angle = std::acos(cosine);
    if (angle < 1e-4f) return glm::normalize(glm::mix(a, b, t));
    if (std::sin(angle) < 1e-4f) return t < 0.5f ? a : b;   // opposite directions: no unique arc between them
    return glm::normalize((std::sin((1.0f - t) * angle) * a + std::sin(t * angle) * b) / std::sin(angle));
}

Camera RecordedPath::at(double seconds) const {
    Camera c;
    c.name = "path";
    if (samples_.empty()) return c;
    double t = samples_.front().seconds + std::max(0.0, seconds);
    auto after = std::upper_bound(samples_.begin(), samples_.end(), t,
                                  [](double value, const Sample& s) { return value < s.seconds; });
    const Sample& a = after == samples_.begin() ? samples_.front() : *(after - 1);
    const Sample& b = after == samples_.end() ? samples_.back() : *after;
    float u = b.seconds > a.seconds ? float((t - a.seconds) / (b.seconds - a.seconds)) : 0.0f;
    u = std::clamp(u, 0.0f, 1.0f);
    c.position = glm::mix(a.position, b.position, u);
    glm::vec3 forward = slerpUnit(a.forward, b.forward, u);
    // Two valid samples on either side of the pole interpolate through it: keep the earlier sample's direction
    // there rather than an undefined view (load() refuses samples along the up axis).
    if (!(glm::length(glm::cross(forward, c.up)) >= 1e-6f)) forward = a.forward;
    c.target = c.position + forward;
    c.verticalFovDegrees = glm::mix(a.verticalFovDegrees, b.verticalFovDegrees, u);
    c.nearPlane = glm::mix(a.nearPlane, b.nearPlane, u);
    return c;
}

void RecordedPath::save(const std::filesystem::path& file, const std::string& scene) const {
    nlohmann::json samples = nlohmann::json::array();
    double start = samples_.empty() ? 0.0 : samples_.front().seconds;
    for (const Sample& s : samples_)
        samples.push_back({{"t", s.seconds - start},
                           {"position", {s.position.x, s.position.y, s.position.z}},
                           {"forward", {s.forward.x, s.forward.y, s.forward.z}},
                           {"fov", s.verticalFovDegrees},
                           {"near", s.nearPlane}});
    nlohmann::json doc = {{"glimmer_camera_path", 1}, {"scene", scene}, {"samples", samples}};
    std::filesystem::path temporary = file;
    temporary += ".tmp";
    {
        std::ofstream out(temporary, std::ios::trunc);
        if (!out) throw Error(file.string() + ": cannot write the camera path");
        out << doc.dump(1) << "\n";
        if (!out) throw Error(file.string() + ": write error");
    }
    std::error_code ec;
    std::filesystem::rename(temporary, file, ec);
    if (ec) throw Error(file.string() + ": cannot write the camera path (" + ec.message() + ")");
}

namespace {

// The limits a sample must keep, the same as a scene file's cameras (scene_file.cpp readCamera): near plane and
// field of view in the ranges there, position within the coordinate limit, the view direction not along the up
// axis (the view matrix would be undefined: every frame one sky colour). Times are finite and at most
// kMaxPathSeconds after the first sample, so frame counts stay far inside int.
constexpr double kMaxPathSeconds = 1e6;
constexpr float kMinFovDegrees = 1.0f, kMaxFovDegrees = 170.0f;

std::string numberText(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

// Reads the JSON values of one sample with errors naming "samples[i].key".
struct SampleReader {
    const nlohmann::json& sample;
    std::string where;

    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw Error(where + (key.empty() ? "" : "." + key) + ": " + what);
    }
    const nlohmann::json* find(const char* key) const {
        auto it = sample.find(key);
        return it == sample.end() ? nullptr : &*it;
    }
    double number(const nlohmann::json& v, const std::string& key) const {
        if (!v.is_number()) fail(key, "expected a number");
        double x = v.get<double>();
        if (!std::isfinite(x)) fail(key, "expected a finite number");
        return x;
    }
    double number(const char* key, double fallback, double lo, double hi) const {
        const nlohmann::json* v = find(key);
        if (!v) return fallback;
        double x = number(*v, key);
        if (!(x >= lo && x <= hi)) fail(key, numberText(x) + " is outside [" + numberText(lo) + ", " + numberText(hi) + "]");
        return x;
    }
    glm::vec3 vec3(const char* key) const {
        const nlohmann::json* v = find(key);
        if (!v) fail(key, "missing (expected [x, y, z])");
        if (!v->is_array() || v->size() != 3) fail(key, "expected [x, y, z]");
        glm::dvec3 out;
        for (int i = 0; i < 3; ++i) out[i] = number((*v)[size_t(i)], std::string(key) + "[" + std::to_string(i) + "]");
        if (glm::any(glm::greaterThan(glm::abs(out), glm::dvec3(kMaxCoordinate))))
            fail(key, "beyond the coordinate limit " + numberText(kMaxCoordinate));
        return glm::vec3(out);
    }
};

}  // namespace

RecordedPath RecordedPath::load(const std::filesystem::path& file) {
    // readInputFile: a regular file of at most 64 MiB (a FIFO or /dev/zero is refused before reading).
    std::string text = readInputFile(file, kCameraPathInput);
    const std::string name = file.string();
    RecordedPath path;
    nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
    if (doc.is_discarded()) throw Error(name + ": not a camera path: invalid JSON");
    if (!doc.is_object()) throw Error(name + ": not a camera path: expected a JSON object");
    if (auto scene = doc.find("scene"); scene != doc.end()) {
        if (!scene->is_string()) throw Error(name + ": scene: expected a string");
        path.sceneName = scene->get<std::string>();
    }
    auto samples = doc.find("samples");
    if (samples == doc.end() || !samples->is_array()) throw Error(name + ": not a camera path: no \"samples\" array");
    if (samples->empty()) throw Error(name + ": camera path has no samples");
    const glm::vec3 up = Camera{}.up;
    for (size_t i = 0; i < samples->size(); ++i) {
        const nlohmann::json& s = (*samples)[i];
        SampleReader r{s, name + ": samples[" + std::to_string(i) + "]"};
        if (!s.is_object()) r.fail("", "expected an object");
        Sample sample;
        if (!r.find("t")) r.fail("t", "missing (seconds)");
        sample.seconds = r.number(*r.find("t"), "t");
        if (!path.samples_.empty() && !(sample.seconds >= path.samples_.back().seconds))
            r.fail("t", "sample times must not decrease (" + numberText(sample.seconds) + " after " +
                            numberText(path.samples_.back().seconds) + ")");
        if (!path.samples_.empty() && !(sample.seconds - path.samples_.front().seconds <= kMaxPathSeconds))
            r.fail("t", numberText(sample.seconds) + " is more than " + numberText(kMaxPathSeconds) +
                            " s after the first sample");
        sample.position = r.vec3("position");
        glm::vec3 forward = r.vec3("forward");
        if (!(glm::length(forward) >= 1e-6f)) r.fail("forward", "is zero");
        sample.forward = glm::normalize(forward);
        if (glm::length(glm::cross(sample.forward, up)) < 1e-6f)
            r.fail("forward", "parallel to the up axis (0, 1, 0): the view is undefined");
        sample.verticalFovDegrees = float(r.number("fov", 45.0, kMinFovDegrees, kMaxFovDegrees));
        sample.nearPlane = float(r.number("near", 0.05, kMinCameraNear, kMaxCameraNear));
        path.samples_.push_back(sample);
    }
    return path;
}

}  // namespace glimmer::ui
