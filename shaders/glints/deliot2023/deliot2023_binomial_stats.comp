// Test kernel: statistics of the gated Gaussian binomial (glints/deliot2023_binomial.glsl, the method's own code)
// over every random pair of the noise texture, for a list of (N, p). One invocation per (texture row, config):
// sum, sum of squares and zero count of its 1024 samples (hard or soft gate), plus P1 (Eq. 16) for the precision check.
#include "common/bindings.glsl"
layout(local_size_x = 64) in;
#include "glints/deliot2023/deliot2023_binomial.glsl"

layout(std430, binding = BINDING_METHOD_LAST - 1) readonly buffer Configs { vec2 u_configs[]; };        // (N, p)
layout(std430, binding = BINDING_METHOD_LAST) writeonly buffer RowSums { dvec4 u_rowSums[]; };       // [config * size + row]
layout(location = 0) uniform int u_softGate;   // 1: the authors' soft gate, 0: Eq. 18's hard gate

void main() {
    uint row = gl_GlobalInvocationID.x, config = gl_GlobalInvocationID.y;
    if (row >= uint(DELIOT_NOISE_SIZE) || config >= uint(u_configs.length())) return;
    float N = u_configs[config].x, p = u_configs[config].y;
    double sum = 0.0, sumSquares = 0.0, zeros = 0.0;
    for (int x = 0; x < DELIOT_NOISE_SIZE; ++x) {
        vec2 r = deliotUnpackNoise(texelFetch(u_deliotNoise, ivec2(x, int(row)), 0).r);
        double count = double(deliotGatedBinomial(N, p, r.x, r.y, u_softGate != 0));
        sum += count;
        sumSquares += count * count;
        zeros += count == 0.0 ? 1.0 : 0.0;
    }
    u_rowSums[config * uint(DELIOT_NOISE_SIZE) + row] = dvec4(sum, sumSquares, zeros, double(deliotProbAtLeastOne(N, p)));
}
