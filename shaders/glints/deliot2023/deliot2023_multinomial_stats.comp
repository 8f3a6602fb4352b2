// Test kernel: statistics of the hierarchical multinomial of Kneiphof & Klein 2025 (glints/deliot2023_multinomial.glsl,
// the method's own code) over the random pairs of deliot2023's noise texture, for a list of configurations
// (n facets, K levels, level probabilities). One invocation per (texture row, config): per level the sum of its
// counts over the row's draws (each draw takes 7 consecutive pairs), and the largest |sum of counts - n|.
#include "common/bindings.glsl"
layout(local_size_x = 64) in;
#include "glints/deliot2023/deliot2023_binomial.glsl"
#include "glints/deliot2023/deliot2023_multinomial.glsl"

struct Config {
    vec4 nLevels;       // x n, y K
    vec4 p[2];          // level probabilities 0..7
};
layout(std430, binding = BINDING_METHOD_LAST - 1) readonly buffer Configs { Config u_configs[]; };
layout(std430, binding = BINDING_METHOD_LAST) writeonly buffer RowSums { double u_rowSums[]; };   // 10 per (config, row)

void main() {
    uint row = gl_GlobalInvocationID.x, config = gl_GlobalInvocationID.y;
    if (row >= uint(DELIOT_NOISE_SIZE) || config >= uint(u_configs.length())) return;
    Config c = u_configs[config];
    float p[8];
    for (int i = 0; i < 8; ++i) p[i] = c.p[i >> 2][i & 3];
    double sums[8] = double[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    double worstConservation = 0.0, sumSquares0 = 0.0;
    Kk25Tree tree = kk25Tree(p, int(c.nLevels.y));
    for (int x = 0; x + 7 <= DELIOT_NOISE_SIZE; x += 7) {
        vec2 rnd[7];
        for (int k = 0; k < 7; ++k) rnd[k] = deliotUnpackNoise(texelFetch(u_deliotNoise, ivec2(x + k, int(row)), 0).r);
        float counts[8];
        kk25Multinomial(c.nLevels.x, tree, rnd, counts);
        float total = 0.0;
        for (int i = 0; i < 8; ++i) {
            sums[i] += double(counts[i]);
            total += counts[i];
        }
        sumSquares0 += double(counts[1]) * double(counts[1]);
        worstConservation = max(worstConservation, abs(double(total) - double(c.nLevels.x)));
    }
    uint base = (config * uint(DELIOT_NOISE_SIZE) + row) * 10u;
    for (int i = 0; i < 8; ++i) u_rowSums[base + uint(i)] = sums[i];
    u_rowSums[base + 8u] = worstConservation;
    u_rowSums[base + 9u] = sumSquares0;
}
