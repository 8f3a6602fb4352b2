#include "ui/recorded_path.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/error.h"
#include "core/files.h"

namespace glimmer::ui {

void RecordedPath::add(double seconds, const Camera& camera, double minSpacing) {
    if (!samples_.empty() && seconds - samples_.back().seconds < minSpacing) return;
    samples_.push_back({seconds, camera.position, camera.forward(), camera.verticalFovDegrees, camera.nearPlane});
}

static glm::vec3 slerpUnit(const glm::vec3& a, const glm::vec3& b, float t) {
    float cosine = std::clamp(glm::dot(a, b), -1.0f, 1.0f);
    float angle = std::acos(cosine);
    if (angle < 1e-4f) return glm::normalize(glm::mix(a, b, t));
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
    c.target = c.position + slerpUnit(a.forward, b.forward, u);
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

RecordedPath RecordedPath::load(const std::filesystem::path& file) {
    std::string text = readTextFile(file);
    RecordedPath path;
    try {
        nlohmann::json doc = nlohmann::json::parse(text);
        if (!doc.is_object() || !doc.contains("samples")) throw Error("no \"samples\" array");
        path.sceneName = doc.value("scene", "");
        auto vec3 = [](const nlohmann::json& v, const char* what) {
            if (!v.is_array() || v.size() != 3) throw Error(std::string("\"") + what + "\" must be [x, y, z]");
            glm::vec3 out{v[0].get<float>(), v[1].get<float>(), v[2].get<float>()};
            if (!std::isfinite(out.x) || !std::isfinite(out.y) || !std::isfinite(out.z))
                throw Error(std::string("\"") + what + "\" is not finite");
            return out;
        };
        for (const nlohmann::json& s : doc.at("samples")) {
            Sample sample;
            sample.seconds = s.at("t").get<double>();
            sample.position = vec3(s.at("position"), "position");
            sample.forward = vec3(s.at("forward"), "forward");
            if (glm::length(sample.forward) < 1e-6f) throw Error("\"forward\" is zero");
            sample.forward = glm::normalize(sample.forward);
            sample.verticalFovDegrees = s.value("fov", 45.0f);
            sample.nearPlane = s.value("near", 0.05f);
            if (!(sample.verticalFovDegrees > 0.0f && sample.verticalFovDegrees < 180.0f)) throw Error("\"fov\" out of (0, 180)");
            if (!path.samples_.empty() && !(sample.seconds >= path.samples_.back().seconds))
                throw Error("sample times must not decrease");
            path.samples_.push_back(sample);
        }
    } catch (const nlohmann::json::exception& e) {
        throw Error(file.string() + ": not a camera path: " + e.what());
    } catch (const Error& e) {
        throw Error(file.string() + ": not a camera path: " + e.what());
    }
    if (path.samples_.empty()) throw Error(file.string() + ": camera path has no samples");
    return path;
}

}  // namespace glimmer::ui
