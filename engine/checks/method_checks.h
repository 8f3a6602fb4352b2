// The interface rules every glint method is held to (shaders/glints/README.md), as one library that both
// `glimmer check-method` and the tests use: convergence to smooth at very high density, the white furnace over
// the area, finite values over a sweep of footprints and angles, cost per pixel relative to smooth, and constant
// time across plane90 / plane25. Rules, measures and limits: docs/user_methods.md#check-method.
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/params.h"
#include "platform/context.h"

namespace glimmer::checks {

// Gap between a glinty and a smooth render of the same view (RGBA32F, same size): the ratio of the image means
// and, after a (2 r + 1)^2 box filter of the per-pixel RGB mean, the relative error per pixel
// |a - b| / max(b, 0.02 mean(b)). Tests of the built-ins and check-method's convergence rule share it.
struct SmoothGap {
    double meanRatio = 0.0;        // mean(glinty) / mean(smooth)
    double worstPixelError = 0.0;  // largest box-filtered relative error
    double fractionAbove = 0.0;    // fraction of pixels whose error exceeds `tolerance`
};
SmoothGap gapToSmooth(const std::vector<float>& glinty, const std::vector<float>& smooth, int width, int height,
                      int boxRadius, double tolerance);

// White furnace over the area (Kemppinen et al. 2025, Fig. 15, applied to any method): the projected-area
// integral of D over half vectors, E_area[ int D(h) (n.h) dh ], which is 1 for a normalized NDF. Estimated with the
// method's real shader (reference/method_probe.h) as the mean of D / D_smooth over half vectors drawn from
// D_smooth (n.h) at `points` uniform positions of a patch of `patchCells` x `patchCells` footprints; the standard
// error comes from the spread of the per-position means.
struct FurnaceCase {
    int ndf = 0;              // 0 GGX, 1 Beckmann
    float alpha = 0.3f;
    float footprint = 1e-3f;  // UV extent of the pixel footprint (duv/dx along u; duv/dy = 0.5 x that along v)
};
struct FurnaceResult {
    double ratio = 0.0, stdError = 0.0;
    size_t samples = 0, nonFinite = 0;
};
// furnace and finiteSweep need a current GL 4.5 context; checkMethod makes its own.
FurnaceResult furnace(const std::string& methodId, const ParamValues& values, const FurnaceCase& c, int points,
                      int halfVectorsPerPoint, const std::filesystem::path& shaderRoot = {});

// Non-finite or negative glintD / AOV values over a sweep of footprints (zero, tiny, huge, degenerate, 10^4
// anisotropy), half vectors up to and at the horizon, roughness, NDF, density scale and UV offsets.
struct FiniteResult {
    size_t evaluated = 0, nonFinite = 0, negative = 0;
    std::string firstBad;   // the inputs of the first offending evaluation
};
FiniteResult finiteSweep(const std::string& methodId, const ParamValues& values,
                         const std::filesystem::path& shaderRoot = {});

struct RuleResult {
    std::string rule;          // convergence, furnace, finite, cost, constant-time
    std::string status;        // "pass", "FAIL", "info"
    std::string measured;      // what was measured, in words and numbers
    std::string limit;         // what passes
};

struct CheckOptions {
    int size = 128;                  // renders of the convergence rule
    int timingSize = 192;            // renders of the cost and constant-time rules
    int timingFrames = 5;            // per scene and method, interleaved, median
    Backend backend = Backend::Egl;
    std::filesystem::path shaderRoot;
    std::vector<std::string> rules;  // empty = every rule
    std::function<void(const std::string&)> progress;
};

struct CheckReport {
    std::string method;
    std::vector<RuleResult> results;
    bool passed() const;
    std::vector<std::string> failedRules() const;
};

const std::vector<std::string>& ruleNames();
CheckReport checkMethod(const std::string& methodId, const CheckOptions& options);
std::string formatTable(const CheckReport& report);

}  // namespace glimmer::checks
