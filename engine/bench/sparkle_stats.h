// Sparkle statistics of a glint method: the distribution of D / D_smooth over the highlight, from the glint AOV
// (the first light's NDF term) of the method and of `smooth` rendered with the same scene, camera and size.
// Used by tools/sparkle_stats.cpp (EXR files) and by the footprint-consistency and sparkle tests (in memory).
#pragma once
#include <cstddef>
#include <vector>

namespace glimmer {

struct SparkleStats {
    size_t pixels = 0;          // highlight pixels measured
    double meanRatio = 0.0;     // mean of D / D_smooth (1 when the method keeps the mean)
    double variance = 0.0;      // variance of D / D_smooth
    double cv = 0.0;            // coefficient of variation: sqrt(variance) / mean
    double p999OverMean = 0.0;  // 99.9th percentile of D / D_smooth over its mean
    double zeroFraction = 0.0;  // fraction of highlight pixels with D == 0
};

// The highlight: pixels whose smooth D is at least `threshold` times the image's largest smooth D.
// `glint` and `smooth` are one value per pixel (same size). Non-finite values are counted as failures by the
// caller (the renderer reports them); here they are skipped.
SparkleStats sparkleStats(const std::vector<float>& glint, const std::vector<float>& smooth, double threshold = 0.1);

// Box-filters a w x h single-channel image by an integer factor (w, h multiples of it).
std::vector<float> boxDownsample(const std::vector<float>& image, int w, int h, int factor);

}  // namespace glimmer
