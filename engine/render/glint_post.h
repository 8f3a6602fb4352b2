// The glint post pass of Wang, Deng & Holzschuch 2020, Sec. 4.4 "Gaussian Blurring" (shaders/post/): its kernel
// weights and a CPU reference of both blurs, used by the tests to check the GL passes pixel by pixel.
#pragma once
#include <vector>

namespace glimmer::glintpost {

constexpr int kMaxRadius = 15;  // u_weights[16] in the shaders

// Radius r of a Gaussian of `taps` taps: (taps - 1) / 2, so an even count acts as the next smaller odd one.
int radiusOf(int taps);
// Weights for |k| = 0..r: binomial coefficients C(2r, r + k) / 4^r (the discrete Gaussian, sigma = sqrt(r / 2));
// they sum to one over k = -r..r. Throws Error when r exceeds kMaxRadius.
std::vector<float> binomialWeights(int radius);

// CPU reference of the post pass on the lighting pass's glint targets (RGBA, row-major, same layout as the GL
// readback): the occlusion blur (visibility in environment.a, renormalised over pixels whose lights.a mask is
// set and over in-image taps), environment rgb x delta + lights rgb, then the glint blur (renormalised over
// in-image taps). Returns the RGB radiance added per pixel (RGBA, a = delta).
std::vector<float> referencePostPass(const std::vector<float>& environment, const std::vector<float>& lights,
                                     int width, int height, int occlusionTaps, int glintTaps);

}  // namespace glimmer::glintpost
