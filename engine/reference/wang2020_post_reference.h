// CPU reference of the Wang et al. 2020 Sec. 4.4 post pass (glints/wang2020/wang2020_post_pass.h), used by the tests to check
// the GL passes pixel by pixel.
#pragma once
#include <vector>

namespace glimmer::glintpost {

// On the lighting pass's glint targets (RGBA, row-major, same layout as the GL readback): the occlusion blur
// (visibility in environment.a, renormalised over pixels whose lights.a mask is set and over in-image taps),
// environment rgb x delta + lights rgb, then the glint blur (renormalised over in-image taps). Returns the RGB
// radiance added per pixel (RGBA, a = delta).
std::vector<float> referencePostPass(const std::vector<float>& environment, const std::vector<float>& lights,
                                     int width, int height, int occlusionTaps, int glintTaps);

}  // namespace glimmer::glintpost
