// Frame-time percentiles for the window's stats strip (recent frames) and `view --frames N --stats` (the run).
// Percentiles are nearest-rank: the value at rank ceil(q n) of the sorted times (the median of an even count is
// the lower middle value), so every reported number is a frame that happened.
#pragma once
#include <cstddef>
#include <vector>

namespace glimmer {

// Nearest-rank percentile, q in [0, 1]; 0 for an empty list.
double percentile(std::vector<double> values, double q);

class FrameTimes {
public:
    explicit FrameTimes(size_t recentCapacity = 120) : capacity_(recentCapacity) {}
    void add(double ms);
    const std::vector<double>& all() const { return all_; }
    // Over the last `recentCapacity` frames.
    double recentPercentile(double q) const { return percentile(recent_, q); }
    double runPercentile(double q) const { return percentile(all_, q); }

private:
    size_t capacity_;
    size_t next_ = 0;
    std::vector<double> recent_;   // ring buffer
    std::vector<double> all_;
};

}  // namespace glimmer
