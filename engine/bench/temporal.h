// `glimmer bench --temporal`: frame-to-frame flicker of the glint term along a short camera path. Each frame's
// glint AOV (D of the first light) is compared with the previous frame's, reprojected on the CPU with the depth
// AOV and both cameras: flicker = mean |D_t - D_{t-1}(reprojected)| / mean D_t over the pixels visible in both.
// A method whose glints stick to the surface scores near the reprojection baseline of smooth; one whose glints
// pop or swim under motion scores higher.
#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "platform/context.h"
#include "scene/camera.h"

namespace glimmer::bench {

// One frame's AOVs, bottom-up rows as read back from GL.
struct GlintFrame {
    Camera camera;
    int width = 0, height = 0;
    std::vector<float> glint;   // D of the first light, one value per pixel
    std::vector<float> depth;   // distance to the camera (m)
    std::vector<uint8_t> valid; // 1 where a surface was hit
};

struct FlickerMeasure {
    double flicker = 0.0;        // mean |difference| / mean current value over matched pixels (0 when none)
    double matchedFraction = 0.0;// matched pixels / pixels of the current frame
};

// Reprojects `previous` into `current` (nearest pixel; a match needs both pixels valid and depths agreeing to 1%).
FlickerMeasure reprojectedFlicker(const GlintFrame& previous, const GlintFrame& current);

// The light-motion measure of TemporalResult::popping for three consecutive frames of a still camera.
double secondDifference(const GlintFrame& before, const GlintFrame& frame, const GlintFrame& after);

// The camera path: `frames` cameras, each dollied forward by `step` x the distance to the target (0 = static).
std::vector<Camera> dollyPath(const Camera& start, int frames, double step);
// The orbit path: `frames` cameras turned about the vertical axis (world +y) through the target by `step` radians
// per frame, still looking at it. Surfaces keep their footprint while the view direction, hence every half vector,
// turns: the motion geometric glint anti-aliasing is for (Chermain et al. 2021).
std::vector<Camera> orbitPath(const Camera& start, int frames, double step);

struct TemporalOptions {
    std::vector<std::string> scenes;     // empty = plane25, atrium
    std::vector<std::string> methods;    // empty = every method of the method table
    std::string camera;
    int width = 640, height = 360;
    int frames = 8;                      // cameras along the path (frames - 1 frame pairs)
    double step = 0.01;
    // "dolly" (step: fraction of the distance), "orbit" (step: radians) or "light" (a still camera; every light
    // turns about the vertical by step radians per frame: light.turn, which takes degrees): the half vectors turn, nothing moves on
    // screen, so the measure has no reprojection error and a still pattern scores exactly 0.
    std::string motion = "dolly";
    Backend backend = Backend::Egl;
    std::filesystem::path shaderRoot;
    std::vector<std::string> extraSets;
    std::optional<std::string> environment;  // --env (default: the scene's)
    std::string ibl = "prefiltered";
    // "" measures D (the glint AOV, unjittered). "off" or "taa" measures the displayed image instead (mean of its
    // sRGB channels; bloom 0, manual exposure) rendered with that aa setting, after 8 still warm-up frames.
    std::string aa;
    std::function<void(const std::string&)> progress;
};

struct TemporalResult {
    std::string scene, method, aa;
    std::vector<double> perPair;         // flicker of each consecutive frame pair
    double meanFlicker = 0.0, maxFlicker = 0.0, matchedFraction = 0.0;
    // motion=light only (a still camera, so pixels correspond exactly): the mean over inner frames of
    // mean |D_t - (D_t-1 + D_t+1) / 2| / mean D_t. A smoothly moving highlight (the smooth method) scores about 0;
    // glints that pop as the half vector sweeps past them score high. -1 for other motions.
    double popping = -1.0;
};

std::vector<TemporalResult> runTemporal(const TemporalOptions& options);
nlohmann::json temporalToJson(const TemporalOptions& options, const std::vector<TemporalResult>& results);
std::string temporalToMarkdown(const std::vector<TemporalResult>& results);

}  // namespace glimmer::bench
