// The post pass of Wang, Deng & Holzschuch 2020, Sec. 4.4 "Gaussian Blurring" (shaders/glints/wang2020/wang2020_glint_*.frag), the passes that the
// wang2020 entry of the method table adds after the lighting pass: `glint_occlusion_blur` blurs the directional
// occlusion (blur_occlusion taps, paper 9), multiplies the environment glints by it and adds the light glints;
// `glint_blur` blurs the result (blur_glints taps, paper 3) and adds it to the HDR radiance. Also the kernel
// weights, which the CPU reference (reference/wang2020_post_reference.h) shares.
#pragma once
#include <filesystem>
#include <vector>

#include "glints/methods.h"

namespace glimmer::glintpost {

constexpr int kMaxRadius = 15;  // u_weights[16] in the shaders

// Radius r of a Gaussian of `taps` taps: (taps - 1) / 2, so an even count acts as the next smaller odd one.
int radiusOf(int taps);
// Weights for |k| = 0..r: binomial coefficients C(2r, r + k) / 4^r (the discrete Gaussian, sigma = sqrt(r / 2));
// they sum to one over k = -r..r. Throws Error when r exceeds kMaxRadius.
std::vector<float> binomialWeights(int radius);

// Both passes, sharing their intermediate targets (GlintMethod::createPasses of wang2020).
MethodPassList createPasses(const std::filesystem::path& shaderRoot);

}  // namespace glimmer::glintpost
