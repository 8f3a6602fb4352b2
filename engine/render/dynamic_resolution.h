// Render scale for the window: the scene renders at scale x the window (0.25 .. 1) and is upscaled for display
// (render/image/upscale.h). With a target frame rate the scale adapts to the measured frame times:
//   - it acts on the median of the frames since its last change (one slow frame does not move it), and only after
//     kSettleFrames frames at the current scale, so the frames it judges were rendered at that scale;
//   - dead band: it lowers the scale when the median exceeds the target frame time, raises it only when the median
//     is under kRaiseBelow x the target, and holds in between (hysteresis: no oscillation around the target);
//   - a change aims at kAim x the target, limited to kMaxStep per change (smooth); lowering assumes frame time
//     ~ scale (the geometry-bound part does not scale, so the pixel model scale^2 would under-correct), raising
//     assumes frame time ~ pixels ~ scale^2 (cautious, no overshoot above the target).
#pragma once
#include <vector>

namespace glimmer {

class DynamicResolution {
public:
    static constexpr float kMinScale = 0.25f, kMaxScale = 1.0f;
    static constexpr int kSettleFrames = 4;
    static constexpr float kRaiseBelow = 0.75f, kAim = 0.85f, kMaxStep = 0.15f;

    // targetFps <= 0: fixed scale. The scale is clamped to [kMinScale, kMaxScale].
    DynamicResolution(float scale = 1.0f, float targetFps = 0.0f);

    void setTargetFps(float fps);
    void setScale(float scale);   // also restarts the measurement
    float targetFps() const { return targetFps_; }
    bool adaptive() const { return targetFps_ > 0.0f; }
    float scale() const { return scale_; }

    // One measured frame (wall milliseconds, rendered at the current scale). Returns whether the scale changed.
    bool addFrame(double frameMs);
    // The internal render size for a window: round(scale x size), at least 1 pixel.
    void internalSize(int windowW, int windowH, int& w, int& h) const;

private:
    float scale_ = 1.0f, targetFps_ = 0.0f;
    std::vector<double> sinceChange_;
};

}  // namespace glimmer
