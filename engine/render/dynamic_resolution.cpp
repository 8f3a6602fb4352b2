#include "render/dynamic_resolution.h"

#include <algorithm>
#include <cmath>

namespace glimmer {

DynamicResolution::DynamicResolution(float scale, float targetFps) {
    setScale(scale);
    setTargetFps(targetFps);
}

void DynamicResolution::setTargetFps(float fps) {
    targetFps_ = std::isfinite(fps) && fps > 0.0f ? fps : 0.0f;
    sinceChange_.clear();
}

void DynamicResolution::setScale(float scale) {
    scale_ = std::clamp(std::isfinite(scale) ? scale : 1.0f, kMinScale, kMaxScale);
    sinceChange_.clear();
}

bool DynamicResolution::addFrame(double frameMs) {
    if (!adaptive() || !std::isfinite(frameMs) || frameMs <= 0.0) return false;
    sinceChange_.push_back(frameMs);
    if (int(sinceChange_.size()) < kSettleFrames) return false;
    std::vector<double> sorted = sinceChange_;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
    double median = sorted[sorted.size() / 2];
    double targetMs = 1000.0 / double(targetFps_);
    if (sinceChange_.size() > 64) sinceChange_.erase(sinceChange_.begin());   // a window, not the whole run
    bool tooSlow = median > targetMs, headroom = median < double(kRaiseBelow) * targetMs;
    if (!tooSlow && !headroom) return false;
    if ((tooSlow && scale_ <= kMinScale) || (headroom && scale_ >= kMaxScale)) return false;
    // Lowering assumes frame time ~ scale (the part that does not scale makes scale^2 under-correct and settle at
    // the band's edge); raising assumes ~ scale^2, the cautious direction, so a raise does not overshoot.
    double ratio = double(kAim) * targetMs / median;
    float wanted = scale_ * float(tooSlow ? ratio : std::sqrt(ratio));
    float next = std::clamp(wanted, scale_ * (1.0f - kMaxStep), scale_ * (1.0f + kMaxStep));
    next = std::clamp(next, kMinScale, kMaxScale);
    if (next == scale_) return false;
    scale_ = next;
    sinceChange_.clear();
    return true;
}

void DynamicResolution::internalSize(int windowW, int windowH, int& w, int& h) const {
    w = std::max(1, int(std::lround(double(windowW) * double(scale_))));
    h = std::max(1, int(std::lround(double(windowH) * double(scale_))));
}

}  // namespace glimmer
