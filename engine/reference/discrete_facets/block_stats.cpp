#include "reference/discrete_facets/block_stats.h"

#include <algorithm>
#include <cmath>

namespace glimmer::facets {

std::vector<bool> highlightMask(const std::vector<float>& smooth, double threshold) {
    float peak = 0.0f;
    for (float v : smooth)
        if (std::isfinite(v)) peak = std::max(peak, v);
    std::vector<bool> mask(smooth.size(), false);
    for (size_t i = 0; i < smooth.size(); ++i) mask[i] = peak > 0.0f && std::isfinite(smooth[i]) && smooth[i] >= threshold * peak;
    return mask;
}

BlockStats blockStats(const std::vector<float>& glint, const std::vector<float>& smooth, const std::vector<bool>& inside,
                      int w, int h, int block) {
    BlockStats s;
    std::vector<double> ratios;
    size_t dark = 0;
    for (int by = 0; by + block <= h; by += block)
        for (int bx = 0; bx + block <= w; bx += block) {
            double sum = 0.0, sumSmooth = 0.0;
            bool whole = true;
            for (int y = by; y < by + block && whole; ++y)
                for (int x = bx; x < bx + block; ++x) {
                    size_t i = size_t(y) * size_t(w) + size_t(x);
                    if (!inside[i] || !std::isfinite(glint[i])) {
                        whole = false;
                        break;
                    }
                    sum += glint[i];
                    sumSmooth += smooth[i];
                }
            if (!whole || !(sumSmooth > 0.0)) continue;
            ratios.push_back(sum / sumSmooth);
            dark += sum == 0.0;
        }
    if (ratios.empty()) return s;
    double total = 0.0, total2 = 0.0;
    for (double r : ratios) total += r, total2 += r * r;
    s.blocks = ratios.size();
    s.mean = total / double(ratios.size());
    double variance = std::max(total2 / double(ratios.size()) - s.mean * s.mean, 0.0);
    s.cv = s.mean > 0.0 ? std::sqrt(variance) / s.mean : 0.0;
    size_t k = std::min(ratios.size() - 1, size_t(std::floor(0.999 * double(ratios.size() - 1))));
    std::nth_element(ratios.begin(), ratios.begin() + std::ptrdiff_t(k), ratios.end());
    s.p999OverMean = s.mean > 0.0 ? ratios[k] / s.mean : 0.0;
    s.darkFraction = double(dark) / double(s.blocks);
    return s;
}

}  // namespace glimmer::facets
