#include "reference/wang2020_post_reference.h"

#include "glints/wang2020/wang2020_post_pass.h"

namespace glimmer::glintpost {

std::vector<float> referencePostPass(const std::vector<float>& environment, const std::vector<float>& lights,
                                     int width, int height, int occlusionTaps, int glintTaps) {
    auto at = [&](int x, int y) { return (size_t(y) * size_t(width) + size_t(x)) * 4; };
    auto inside = [&](int x, int y) { return x >= 0 && y >= 0 && x < width && y < height; };
    int ro = radiusOf(occlusionTaps), rg = radiusOf(glintTaps);
    std::vector<float> wo = binomialWeights(ro), wg = binomialWeights(rg);

    // Occlusion blur as a direct 2D sum (the shader's separable form computes the same quantity).
    std::vector<float> occluded(environment.size(), 0.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double visible = 0.0, weight = 0.0;
            for (int j = -ro; j <= ro; ++j)
                for (int i = -ro; i <= ro; ++i) {
                    if (!inside(x + i, y + j)) continue;
                    size_t q = at(x + i, y + j);
                    double w = double(wo[size_t(i < 0 ? -i : i)]) * wo[size_t(j < 0 ? -j : j)] * lights[q + 3];
                    visible += w * environment[q + 3];
                    weight += w;
                }
            double delta = weight > 0.0 ? visible / weight : 1.0;
            size_t p = at(x, y);
            for (int c = 0; c < 3; ++c) occluded[p + size_t(c)] = float(environment[p + size_t(c)] * delta + lights[p + size_t(c)]);
            occluded[p + 3] = float(delta);
        }

    std::vector<float> result(environment.size(), 0.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double sum[3] = {0, 0, 0}, weight = 0.0;
            for (int j = -rg; j <= rg; ++j)
                for (int i = -rg; i <= rg; ++i) {
                    if (!inside(x + i, y + j)) continue;
                    size_t q = at(x + i, y + j);
                    double w = double(wg[size_t(i < 0 ? -i : i)]) * wg[size_t(j < 0 ? -j : j)];
                    for (int c = 0; c < 3; ++c) sum[c] += w * occluded[q + size_t(c)];
                    weight += w;
                }
            size_t p = at(x, y);
            for (int c = 0; c < 3; ++c) result[p + size_t(c)] = float(sum[c] / weight);
            result[p + 3] = occluded[p + 3];
        }
    return result;
}

}  // namespace glimmer::glintpost
