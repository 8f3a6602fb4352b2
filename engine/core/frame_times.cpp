#include "core/frame_times.h"

#include <algorithm>
#include <cmath>

namespace glimmer {

double percentile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    q = std::clamp(q, 0.0, 1.0);
    size_t rank = size_t(std::ceil(q * double(values.size())));
    size_t index = rank == 0 ? 0 : rank - 1;
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(index), values.end());
    return values[index];
}

void FrameTimes::add(double ms) {
    all_.push_back(ms);
    if (recent_.size() < capacity_) {
        recent_.push_back(ms);
    } else if (capacity_ > 0) {
        recent_[next_] = ms;
        next_ = (next_ + 1) % capacity_;
    }
}

}  // namespace glimmer
