#include "glints/deliot2023/deliot2023_noise.h"

#include <algorithm>
#include <cmath>

namespace glimmer::deliot2023 {

// 32-bit mixing (a murmur-style finalizer) for the noise texture generator.
static uint32_t mix32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

static double unit(uint32_t bits) { return (double(bits >> 8) + 0.5) / double(1u << 24); }

std::vector<uint32_t> makeNoiseTexels(uint32_t seed) {
    std::vector<uint32_t> texels(size_t(kNoiseSize) * kNoiseSize);
    constexpr double kTwoPi = 6.283185307179586;
    for (size_t i = 0; i < texels.size(); ++i) {
        uint32_t h0 = mix32(uint32_t(i) * 3u + seed);
        uint32_t h1 = mix32(h0 ^ 0x68bc21ebu), h2 = mix32(h1 ^ 0x02e5be93u);
        // 16-bit fixed point: the uniform as t^4 with t = (k + 0.5) / 65536 and k = floor(65536 U^(1/4)) (fine
        // resolution near 0 for tiny gate probabilities; u < 1 so a gate of probability 1 always opens); the
        // Gaussian as k / 4096 clamped to the signed 16-bit range (|g| < 8).
        uint32_t u = std::min(uint32_t(65536.0 * std::pow(unit(h0), 0.25)), 65535u);
        double gaussian = std::sqrt(-2.0 * std::log(unit(h1))) * std::cos(kTwoPi * unit(h2));   // Box-Muller
        int32_t g = int32_t(std::lround(std::clamp(gaussian * 4096.0, -32768.0, 32767.0)));
        texels[i] = u | (uint32_t(g) << 16);
    }
    return texels;
}

}  // namespace glimmer::deliot2023
