#include "bench/temporal.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "glints/methods.h"
#include "render/aov.h"
#include "offscreen/offscreen.h"

namespace glimmer::bench {

FlickerMeasure reprojectedFlicker(const GlintFrame& previous, const GlintFrame& current) {
    const int w = current.width, h = current.height;
    glm::dmat4 toPrevious = glm::dmat4(previous.camera.projection(float(previous.width) / float(previous.height))) *
                            glm::dmat4(previous.camera.view());
    double differenceSum = 0.0, valueSum = 0.0;
    size_t matched = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            size_t i = size_t(y) * w + x;
            if (!current.valid[i]) continue;
            Ray ray = cameraRay(current.camera, w, h, x + 0.5, y + 0.5);
            glm::dvec3 world = ray.origin + ray.direction * double(current.depth[i]);
            glm::dvec4 clip = toPrevious * glm::dvec4(world, 1.0);
            if (clip.w <= 0.0) continue;
            double px = (clip.x / clip.w * 0.5 + 0.5) * previous.width;
            double py = (clip.y / clip.w * 0.5 + 0.5) * previous.height;
            int ix = int(std::floor(px)), iy = int(std::floor(py));
            if (ix < 0 || iy < 0 || ix >= previous.width || iy >= previous.height) continue;
            size_t j = size_t(iy) * previous.width + ix;
            if (!previous.valid[j]) continue;
            // Disocclusion: the previous pixel must see the same surface point (distance within 1%).
            double expected = glm::length(world - glm::dvec3(previous.camera.position));
            if (std::abs(expected - double(previous.depth[j])) > 0.01 * expected + 1e-4) continue;
            double a = current.glint[i], b = previous.glint[j];
            if (!std::isfinite(a) || !std::isfinite(b)) continue;
            differenceSum += std::abs(a - b);
            valueSum += std::abs(a);
            ++matched;
        }
    FlickerMeasure m;
    m.matchedFraction = double(matched) / double(std::max(1, w * h));
    m.flicker = valueSum > 0.0 ? differenceSum / valueSum : 0.0;  // both means share the pixel count
    return m;
}

std::vector<Camera> dollyPath(const Camera& start, int frames, double step) {
    std::vector<Camera> path;
    glm::vec3 offset = start.target - start.position;
    for (int i = 0; i < frames; ++i) {
        Camera c = start;
        glm::vec3 move = offset * float(step * i);
        c.position += move;
        c.target += move;
        c.name = start.name + "+dolly" + std::to_string(i);
        path.push_back(c);
    }
    return path;
}

static GlintFrame captureFrame(OffscreenSession& session, RenderRequest request, const Camera& camera) {
    request.cameraOverride = camera;
    GlintFrame frame;
    frame.camera = camera;
    frame.width = request.width;
    frame.height = request.height;
    request.settings.debugView = findAov("glint").viewId;
    RenderResult glint = session.render(request);
    request.settings.debugView = findAov("depth").viewId;
    RenderResult depth = session.render(request);
    size_t n = size_t(frame.width) * frame.height;
    frame.glint.resize(n);
    frame.depth.resize(n);
    frame.valid.resize(n);
    for (size_t i = 0; i < n; ++i) {
        frame.glint[i] = glint.hdr[i * 4];
        frame.depth[i] = depth.hdr[i * 4];
        frame.valid[i] = depth.hdr[i * 4 + 3] > 0.0f && std::isfinite(depth.hdr[i * 4]);
    }
    return frame;
}

// The displayed image along the path (the history of aa=taa carries from frame to frame): depth AOVs first (a
// debug view resets TAA), then the final image after `warmup` still frames at the first camera.
static std::vector<GlintFrame> captureImagePath(OffscreenSession& session, RenderRequest request,
                                                const std::vector<Camera>& path, const std::string& aa) {
    std::vector<GlintFrame> frames;
    for (const Camera& camera : path) {
        request.cameraOverride = camera;
        request.settings.debugView = findAov("depth").viewId;
        RenderResult depth = session.render(request);
        GlintFrame frame;
        frame.camera = camera;
        frame.width = request.width;
        frame.height = request.height;
        size_t n = size_t(frame.width) * frame.height;
        frame.depth.resize(n);
        frame.valid.resize(n);
        frame.glint.resize(n);
        for (size_t i = 0; i < n; ++i) {
            frame.depth[i] = depth.hdr[i * 4];
            frame.valid[i] = depth.hdr[i * 4 + 3] > 0.0f && std::isfinite(depth.hdr[i * 4]);
        }
        frames.push_back(std::move(frame));
    }
    request.settings.debugView = 0;
    request.settings.apply("aa=" + aa);
    request.cameraOverride = path.front();
    request.frames = 8;   // still warm-up: TAA's history converges before the camera moves
    for (size_t k = 0; k < path.size(); ++k) {
        request.cameraOverride = path[k];
        RenderResult image = session.render(request);
        request.frames = 1;
        for (size_t i = 0; i < frames[k].glint.size(); ++i)
            frames[k].glint[i] = (float(image.display[i * 4]) + float(image.display[i * 4 + 1]) +
                                  float(image.display[i * 4 + 2])) / (3.0f * 255.0f);
    }
    return frames;
}

std::vector<TemporalResult> runTemporal(const TemporalOptions& options) {
    std::vector<std::string> scenes = options.scenes.empty() ? std::vector<std::string>{"plane25", "atrium"}
                                                             : options.scenes;
    std::vector<std::string> methods;
    if (options.methods.empty())
        for (const GlintMethod& m : glintMethods()) methods.push_back(m.id);
    else
        for (const std::string& id : options.methods) methods.push_back(findGlintMethod(id).id);

    std::vector<TemporalResult> results;
    for (const std::string& scene : scenes) {
        RenderRequest request;
        request.scene = scene;
        request.camera = options.camera;
        request.width = options.width;
        request.height = options.height;
        request.backend = options.backend;
        request.shaderRoot = options.shaderRoot;
        request.environment = options.environment;
        request.settings.method = methods.front();
        request.settings.ibl = options.ibl;
        OffscreenSession session(request);
        std::vector<Camera> path = dollyPath(session.scene().camera(options.camera), options.frames, options.step);
        for (const std::string& method : methods) {
            request.settings = RenderSettings();
            request.settings.method = method;
            request.settings.ibl = options.ibl;
            for (const std::string& set : options.extraSets) request.settings.apply(set);
            TemporalResult result{scene, method, options.aa, {}, 0, 0, 0};
            std::vector<GlintFrame> imagePath;
            if (!options.aa.empty()) imagePath = captureImagePath(session, request, path, options.aa);
            GlintFrame previous = imagePath.empty() ? captureFrame(session, request, path.front()) : imagePath[0];
            for (size_t k = 1; k < path.size(); ++k) {
                GlintFrame current = imagePath.empty() ? captureFrame(session, request, path[k]) : imagePath[k];
                FlickerMeasure m = reprojectedFlicker(previous, current);
                result.perPair.push_back(m.flicker);
                result.matchedFraction += m.matchedFraction / double(path.size() - 1);
                previous = std::move(current);
            }
            for (double f : result.perPair) {
                result.meanFlicker += f / double(result.perPair.size());
                result.maxFlicker = std::max(result.maxFlicker, f);
            }
            if (options.progress) {
                char line[200];
                std::snprintf(line, sizeof line, "temporal %s %s: flicker mean %.4f max %.4f (matched %.0f%%)",
                              scene.c_str(), method.c_str(), result.meanFlicker, result.maxFlicker,
                              100.0 * result.matchedFraction);
                options.progress(line);
            }
            results.push_back(std::move(result));
        }
    }
    return results;
}

nlohmann::json temporalToJson(const TemporalOptions& options, const std::vector<TemporalResult>& results) {
    nlohmann::json rows = nlohmann::json::array();
    for (const TemporalResult& r : results)
        rows.push_back({{"scene", r.scene},
                        {"method", r.method},
                        {"aa", r.aa.empty() ? "glint AOV" : r.aa},
                        {"flicker_mean", r.meanFlicker},
                        {"flicker_max", r.maxFlicker},
                        {"flicker_per_pair", r.perPair},
                        {"matched_fraction", r.matchedFraction}});
    return {{"schema", "glimmer-bench-temporal/1"},
            {"meta",
             {{"resolution", {options.width, options.height}},
              {"frames", options.frames},
              {"dolly_step", options.step},
              {"definition", "mean |D_t - reprojected D_t-1| / mean D_t over pixels visible in both frames "
                             "(glint AOV = D of the first light; nearest-pixel reprojection with depth test)"}}},
            {"results", rows}};
}

std::string temporalToMarkdown(const std::vector<TemporalResult>& results) {
    std::ostringstream out;
    out << "| scene | method | measured | flicker (mean) | flicker (max) | matched pixels |\n"
           "|---|---|---|---|---|---|\n";
    char line[200];
    for (const TemporalResult& r : results) {
        std::snprintf(line, sizeof line, "| %s | %s | %s | %.4f | %.4f | %.0f%% |\n", r.scene.c_str(),
                      r.method.c_str(), r.aa.empty() ? "D (glint AOV)" : ("image, aa=" + r.aa).c_str(), r.meanFlicker, r.maxFlicker, 100.0 * r.matchedFraction);
        out << line;
    }
    return out.str();
}

}  // namespace glimmer::bench
