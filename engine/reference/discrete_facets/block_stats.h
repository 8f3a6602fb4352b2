// Block statistics of a glint image against smooth: the measure of issue 36 (docs/glint_statistics.md).
#pragma once
#include <cstddef>
#include <vector>

namespace glimmer::facets {

// Statistics of sum(D) / sum(D_smooth) over square blocks of `block` x `block` pixels that lie wholly inside the
// highlight (`inside` per pixel; e.g. smooth D >= 0.1 of its peak on a glinty material). Summing over blocks
// before dividing makes methods with different pixel filters comparable (issue 36; docs/glint_statistics.md).
struct BlockStats {
    size_t blocks = 0;
    double mean = 0.0;          // mean of the block ratios
    double cv = 0.0;            // their standard deviation / mean
    double p999OverMean = 0.0;  // 99.9th percentile / mean
    double darkFraction = 0.0;  // blocks whose sum of D is 0 (no reflecting facet)
};
BlockStats blockStats(const std::vector<float>& glint, const std::vector<float>& smooth, const std::vector<bool>& inside,
                      int w, int h, int block);

// The highlight mask of sparkleStats: smooth >= threshold x its peak (finite values only).
std::vector<bool> highlightMask(const std::vector<float>& smooth, double threshold = 0.1);

}  // namespace glimmer::facets
