// The random-number texture of Deliot & Belcour 2023 (shaders/glints/deliot2023/deliot2023_binomial.glsl, u_deliotNoise):
// generated on the CPU once per context by the method's resources; the CPU reference unpacks the same texels.
#pragma once
#include <cstdint>
#include <vector>

namespace glimmer::deliot2023 {

constexpr int kNoiseSize = 1024;   // DELIOT_NOISE_SIZE in deliot2023_binomial.glsl
constexpr uint32_t kNoiseSeed = 0x9e3779b9u;

// R32UI texels, row-major; each packs (uniform in [0, 1), standard normal) as 16-bit fixed point (low half: uniform
// ((k + 0.5) / 65536)^4, high half: signed Gaussian k / 4096).
// Deterministic for a seed.
std::vector<uint32_t> makeNoiseTexels(uint32_t seed = kNoiseSeed);

}  // namespace glimmer::deliot2023
