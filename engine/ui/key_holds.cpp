#include "ui/key_holds.h"

#include <algorithm>
#include <limits>

namespace glimmer::ui {

static constexpr double kOpen = std::numeric_limits<double>::infinity();

void KeyHolds::press(int key, double seconds) {
    std::vector<Hold>& holds = holds_[key];
    if (!holds.empty() && holds.back().end == kOpen) return;  // auto-repeat or a second press without release
    holds.push_back({seconds, kOpen});
}

void KeyHolds::release(int key, double seconds) {
    auto it = holds_.find(key);
    if (it == holds_.end() || it->second.empty() || it->second.back().end != kOpen) return;
    Hold& hold = it->second.back();
    hold.end = std::max(seconds, hold.start + kMinimumTapSeconds);
}

void KeyHolds::releaseAll(double seconds) {
    for (auto& [key, holds] : holds_)
        if (!holds.empty() && holds.back().end == kOpen) release(key, seconds);
}

bool KeyHolds::down(int key) const {
    auto it = holds_.find(key);
    return it != holds_.end() && !it->second.empty() && it->second.back().end == kOpen;
}

double KeyHolds::heldSeconds(int key, double from, double to) const {
    auto it = holds_.find(key);
    if (it == holds_.end() || !(to > from)) return 0.0;
    double total = 0.0;
    for (const Hold& hold : it->second) total += std::max(0.0, std::min(to, hold.end) - std::max(from, hold.start));
    return total;
}

void KeyHolds::forgetBefore(double seconds) {
    for (auto& [key, holds] : holds_)
        std::erase_if(holds, [&](const Hold& h) { return h.end < seconds; });
}

}  // namespace glimmer::ui
