#include "bench/window_image.h"

#include <algorithm>
#include <cmath>

#include "render/aov.h"

namespace glimmer {

std::vector<uint8_t> glintyPixelMask(OffscreenSession& session, RenderRequest request) {
    request.settings.debugView = findAov("material").viewId;
    request.settings.apply("aa=off");
    request.renderScale = 1.0f;
    request.frames = 1;
    RenderResult aov = session.render(request);
    const Scene& scene = session.scene();
    std::vector<uint8_t> mask(size_t(request.width) * size_t(request.height), 0);
    for (size_t i = 0; i < mask.size(); ++i) {
        if (aov.hdr[i * 4 + 3] <= 0.0f) continue;   // sky
        int material = int(std::lround(aov.hdr[i * 4 + 2]));
        mask[i] = material >= 0 && size_t(material) < scene.materials.size() && scene.materials[size_t(material)].glinty;
    }
    return mask;
}

namespace {
template <typename Luminance>
StillImageChange compare(size_t pixels, const std::vector<uint8_t>& mask, float floor, Luminance luminance) {
    StillImageChange change;
    size_t above2 = 0, above10 = 0;
    for (size_t i = 0; i < pixels && i < mask.size(); ++i) {
        if (!mask[i]) continue;
        auto [a, b] = luminance(i);
        double relative = std::abs(a - b) / std::max({a, b, double(floor)});
        ++change.pixels;
        above2 += relative > 0.02;
        above10 += relative > 0.10;
        change.maxRelative = std::max(change.maxRelative, relative);
    }
    if (change.pixels) {
        change.above2 = double(above2) / double(change.pixels);
        change.above10 = double(above10) / double(change.pixels);
    }
    return change;
}
}  // namespace

StillImageChange stillImageChange(const std::vector<float>& a, const std::vector<float>& b,
                                  const std::vector<uint8_t>& mask, float floor) {
    return compare(std::min(a.size(), b.size()) / 4, mask, floor,
                   [&](size_t i) { return std::pair{pixelLuminance(a, i), pixelLuminance(b, i)}; });
}

StillImageChange stillImageChange(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b,
                                  const std::vector<uint8_t>& mask, float floor) {
    auto luma = [](const std::vector<uint8_t>& p, size_t i) {
        return 0.2126 * p[i * 4] + 0.7152 * p[i * 4 + 1] + 0.0722 * p[i * 4 + 2];
    };
    return compare(std::min(a.size(), b.size()) / 4, mask, floor,
                   [&](size_t i) { return std::pair{luma(a, i), luma(b, i)}; });
}

size_t glintPixelCount(const std::vector<float>& hdr, const std::vector<float>& smoothHdr,
                       const std::vector<uint8_t>& mask, float factor, float floor) {
    size_t count = 0;
    const size_t pixels = std::min({hdr.size() / 4, smoothHdr.size() / 4, mask.size()});
    for (size_t i = 0; i < pixels; ++i) {
        if (!mask[i]) continue;
        double value = pixelLuminance(hdr, i), smooth = pixelLuminance(smoothHdr, i);
        count += value > double(factor) * smooth && value > double(floor);
    }
    return count;
}

}  // namespace glimmer
