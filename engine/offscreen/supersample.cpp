#include "offscreen/supersample.h"

#include <cmath>

#include "core/error.h"
#include "render/image/tone_curves.h"

namespace glimmer::image {

std::vector<float> boxDownsample(const std::vector<float>& rgba, int width, int height, int factor) {
    std::vector<float> out(size_t(width) * height * 4, 0.0f);
    const int bigWidth = width * factor;
    const float scale = 1.0f / float(factor * factor);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int sy = 0; sy < factor; ++sy)
                for (int sx = 0; sx < factor; ++sx) {
                    size_t from = (size_t(y * factor + sy) * bigWidth + size_t(x * factor + sx)) * 4;
                    size_t to = (size_t(y) * width + x) * 4;
                    for (int c = 0; c < 4; ++c) out[to + c] += rgba[from + c] * scale;
                }
    return out;
}

RenderResult supersampledRender(const RenderRequest& request,
                                const std::function<RenderResult(const RenderRequest&)>& renderOnce) {
    const int factor = int(request.settings.value(param::ssaa_factor));
    RenderRequest big = request;
    big.width = request.width * factor;
    big.height = request.height * factor;
    if (big.width > 16384 || big.height > 16384)
        throw UsageError("--set aa=ssaa: " + std::to_string(big.width) + "x" + std::to_string(big.height) +
                         " is too large (lower ssaa.factor or --size)");
    big.settings.apply("aa=off");
    big.frames = 1;
    big.renderScale = 1.0f;   // the reference is rendered at the full size
    RenderResult result = renderOnce(big);
    result.hdr = boxDownsample(result.hdr, request.width, request.height, factor);
    result.width = request.width;
    result.height = request.height;
    const float exposure = std::exp2(request.settings.value(param::exposure));
    const auto curve = ToneCurve(int(request.settings.value(param::tonemap)));
    result.display.assign(size_t(request.width) * request.height * 4, 255);
    for (size_t i = 0; i < size_t(request.width) * request.height; ++i) {
        glm::vec3 c = linearToSrgb(applyToneCurve(curve, glm::vec3(result.hdr[i * 4], result.hdr[i * 4 + 1],
                                                                   result.hdr[i * 4 + 2]) * exposure));
        for (int k = 0; k < 3; ++k) result.display[i * 4 + k] = uint8_t(std::lround(c[k] * 255.0f));
    }
    result.stats["resolution"] = {request.width, request.height};
    result.stats["image"]["aa"] = "ssaa";
    result.stats["image"]["ssaa_factor"] = factor;
    return result;
}

}  // namespace glimmer::image
