// Measures of the image the window shows (issue 39): a still camera must give a still image, and every method
// must show its glints at the window's render scale where it shows them at scale 1. Used by tools/window_image.cpp
// (the measurements in docs/window.md) and by tests/window_image_test.cpp (the same measures at CI size).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "offscreen/offscreen.h"

namespace glimmer {

// Pixels (request's output size, bottom-up like the renderer's images) whose surface has a glinty material:
// from the `material` AOV rendered at scale 1 without anti-aliasing.
std::vector<uint8_t> glintyPixelMask(OffscreenSession& session, RenderRequest request);

// Relative change of each masked pixel's luminance between two RGBA images of the same size (HDR radiance or
// 8-bit display values): |a - b| / max(a, b, floor). `floor` keeps near-black pixels from counting (HDR: a small
// radiance; display: a few 8-bit steps).
struct StillImageChange {
    size_t pixels = 0;            // masked pixels compared
    double above2 = 0.0;          // fraction of them that changed by more than 2%
    double above10 = 0.0;         // ... by more than 10%
    double maxRelative = 0.0;     // the largest relative change
};
StillImageChange stillImageChange(const std::vector<float>& a, const std::vector<float>& b,
                                  const std::vector<uint8_t>& mask, float floor);
StillImageChange stillImageChange(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b,
                                  const std::vector<uint8_t>& mask, float floor = 4.0f);

// Glint pixels: masked pixels whose HDR luminance exceeds `factor` x the luminance of the same pixel in the
// `smooth` render (the method's mean without glints) and `floor`: the pixels a player sees sparkle.
size_t glintPixelCount(const std::vector<float>& hdr, const std::vector<float>& smoothHdr,
                       const std::vector<uint8_t>& mask, float factor = 2.0f, float floor = 1e-3f);

// Rec. 709 luminance of RGBA float pixel i.
inline double pixelLuminance(const std::vector<float>& rgba, size_t i) {
    return 0.2126 * rgba[i * 4] + 0.7152 * rgba[i * 4 + 1] + 0.0722 * rgba[i * 4 + 2];
}

}  // namespace glimmer
