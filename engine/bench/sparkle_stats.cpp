#include "bench/sparkle_stats.h"

#include <algorithm>
#include <cmath>

namespace glimmer {

SparkleStats sparkleStats(const std::vector<float>& glint, const std::vector<float>& smooth, double threshold) {
    SparkleStats s;
    float peak = 0.0f;
    for (float v : smooth)
        if (std::isfinite(v)) peak = std::max(peak, v);
    if (!(peak > 0.0f) || glint.size() != smooth.size()) return s;
    std::vector<double> ratios;
    size_t zeros = 0;
    for (size_t i = 0; i < smooth.size(); ++i) {
        if (!std::isfinite(glint[i]) || !(smooth[i] >= threshold * peak)) continue;
        ratios.push_back(double(glint[i]) / smooth[i]);
        zeros += glint[i] == 0.0f;
    }
    if (ratios.empty()) return s;
    double sum = 0.0, sum2 = 0.0;
    for (double r : ratios) sum += r, sum2 += r * r;
    s.pixels = ratios.size();
    s.meanRatio = sum / ratios.size();
    s.variance = std::max(sum2 / ratios.size() - s.meanRatio * s.meanRatio, 0.0);
    s.cv = s.meanRatio > 0.0 ? std::sqrt(s.variance) / s.meanRatio : 0.0;
    size_t k = std::min(ratios.size() - 1, size_t(std::floor(0.999 * (ratios.size() - 1))));
    std::nth_element(ratios.begin(), ratios.begin() + k, ratios.end());
    s.p999OverMean = s.meanRatio > 0.0 ? ratios[k] / s.meanRatio : 0.0;
    s.zeroFraction = double(zeros) / s.pixels;
    return s;
}

std::vector<float> boxDownsample(const std::vector<float>& image, int w, int h, int factor) {
    int ow = w / factor, oh = h / factor;
    std::vector<float> out(size_t(ow) * oh, 0.0f);
    for (int y = 0; y < oh * factor; ++y)
        for (int x = 0; x < ow * factor; ++x) out[size_t(y / factor) * ow + x / factor] += image[size_t(y) * w + x];
    for (float& v : out) v /= float(factor * factor);
    return out;
}

}  // namespace glimmer
