// What the lighting pass saw the glint method produce, before any clamp (shaders/frame/method_output_check.glsl):
// counters in a small storage buffer, incremented with atomics only on the pixels where something is wrong, plus
// a sparse sample (every 4th pixel in x and y) that measures how often D exceeds the smooth NDF by far. The
// offscreen renderer reads them after each render, reports them in --stats and warns naming the method:
// a NaN, infinite or negative D, non-finite or negative radiance, or an implausible D never make a silent image.
#pragma once
#include <glad/gl.h>

#include <cstdint>
#include <string>

#include "gl/handles.h"

namespace glimmer {

struct MethodOutputCounts {
    uint64_t sampledEvaluations = 0;   // glintD calls at the sampled pixels (every 4th in x and y)
    uint64_t sampledFarAboveSmooth = 0;// ... whose D exceeded 4 x D_smooth(h) + 1
    uint64_t nonFiniteD = 0;           // glintD (or glintColorD) returned NaN or Inf
    uint64_t negativeD = 0;            // ... a negative value
    uint64_t nonFiniteRadiance = 0;    // radiance channels that were NaN or Inf before the lighting pass zeroed them
    uint64_t negativeRadiance = 0;     // radiance channels below 0 before the lighting pass clamped them

    // An energy-conserving method (E[D] = D_smooth, what check-method's convergence and furnace rules test) has
    // D > 4 D_smooth on at most a quarter of its evaluations (Markov's inequality); more than half, over at least
    // kMinSampledEvaluations, is implausible (a loop that runs to llvmpipe's 65535-iteration cap gives ~1e6).
    static constexpr uint64_t kMinSampledEvaluations = 64;
    static constexpr double kImplausibleFraction = 0.5;
    double farAboveSmoothFraction() const {
        return sampledEvaluations ? double(sampledFarAboveSmooth) / double(sampledEvaluations) : 0.0;
    }
    bool implausible() const {
        return sampledEvaluations >= kMinSampledEvaluations && farAboveSmoothFraction() > kImplausibleFraction;
    }
    bool anyProblem() const { return nonFiniteD || negativeD || nonFiniteRadiance || negativeRadiance || implausible(); }
    // One line per problem for `method` ("" when none), e.g. "method 'mine': glintD returned NaN or Inf 4096 times
    // (those lights add nothing)".
    std::string describe(const std::string& method) const;
};

class MethodOutputCheck {
public:
    MethodOutputCheck();
    void bind() const;     // at BINDING_METHOD_OUTPUT (storage) for the lighting pass
    void reset();
    // Waits for the GPU (a readback): call once per render, not per frame.
    MethodOutputCounts read() const;

private:
    gl::Buffer counters_;
};

}  // namespace glimmer
