// Auto-exposure pass (shaders/image/luminance_histogram.comp, exposure_adapt.comp; docs/image.md): a log2-luminance
// histogram of the HDR radiance (after TAA, before bloom), its trimmed mean mapped to middle grey, adapted over
// time. Reads the post HDR radiance; writes its state buffer (FrameResource::ExposureState, BINDING_EXPOSURE_STATE:
// metered EV, target EV), which the tone-mapping pass reads on the GPU (no readback in the frame). Compute only: no
// fixed-function state applies.
#pragma once
#include <filesystem>
#include <vector>

#include "gl/handles.h"
#include "render/frame/pass.h"

namespace glimmer {

class ExposurePass : public Pass {
public:
    explicit ExposurePass(const std::filesystem::path& shaderRoot);
    const char* name() const override { return "exposure"; }
    PassResources resources() const override {
        return {.reads = {FrameResource::PostHdr}, .writes = {FrameResource::ExposureState}};
    }
    std::vector<gl::Program*> programs() override { return {&histogram_, &adapt_}; }
    void prepare(PrepareContext& context) override;
    bool runs(const FrameContext& frame) const override { return wanted(frame.settings); }
    void execute(const FrameContext& frame) override;
    // exposure=auto on the final image.
    static bool wanted(const RenderSettings& settings);

    // Weight in [0, 1] of each frame's metered value (1: converged at once, the offscreen default; the window
    // passes 1 - exp(-dt / time constant)).
    void setAdaptation(float weight) { adaptation_ = weight; }
    // Read back (tests, --stats): the exposure in EV applied by the tone-mapping pass, and this frame's target.
    float meteredEv() const;
    float targetEv() const;

    static constexpr float kLowPercentile = 0.4f, kHighPercentile = 0.95f;

private:
    gl::Program histogram_, adapt_;
    gl::Buffer histogramBins_, state_;
    float adaptation_ = 1.0f;
};

}  // namespace glimmer
