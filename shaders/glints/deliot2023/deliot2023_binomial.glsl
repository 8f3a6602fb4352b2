// Deliot & Belcour 2023, "Real-time rendering of glinty appearances using distributed binomial laws on
// anisotropic grids": the random-number plumbing and the gated Gaussian binomial approximation (Sec. 6.3).
// Shared by glints/deliot2023.glsl and the statistical tests (tests/deliot2023_test.cpp compiles a compute
// shader that includes this file), so the tests exercise exactly the code the method runs.
// CPU mirror: engine/reference/deliot2023_reference.{h,cpp}; keep both in step.
#include "common/bindings.glsl"

// Sec. 6.3: random numbers come from a small texture generated once at start-up
// (engine/glints/deliot2023/deliot2023_resources.cpp): 1024 x 1024 R32UI texels, each one (uniform, Gaussian) pair packed as
// 16-bit fixed point. Low half: the uniform u as t^4, t = (k + 0.5) / 65536 (k drawn so that u is uniform), which
// resolves gate probabilities down to ~1e-12 (a linear 16-bit u could not tell P1 = 1e-7 from 1.5e-5); high half:
// the signed Gaussian k / 4096. Integer texture: no filtering, no NaN bit patterns; a few multiplies to unpack
// (half floats cost more on llvmpipe).
// Angular cell (a, b) of a spatial vertex lives in texel vertexTexel + (a, b), so a cell keeps its random numbers
// whichever 2x2 bilinear neighbourhood it is part of (no jumps as h moves), and the 4 cells of a neighbourhood are
// one textureGather (4 texelFetch per vertex made the noise reads most of the method's cost on llvmpipe).
layout(binding = UNIT_METHOD_FIRST) uniform usampler2D u_deliotNoise;   // NEAREST, REPEAT
const int DELIOT_NOISE_SIZE = 1024;   // must match kNoiseSize in engine/glints/deliot2023/deliot2023_noise.h

// Packed pairs of angular cells a0 + (0, 1), a0 + (1, 1), a0 + (1, 0), a0 (textureGather's component order).
uvec4 deliotNoiseGather(ivec2 vertexTexel, ivec2 a0) {
    ivec2 corner = (vertexTexel + a0 + 1) & (DELIOT_NOISE_SIZE - 1);   // shared corner of the 2x2 texel block
    return textureGather(u_deliotNoise, vec2(corner) * (1.0 / float(DELIOT_NOISE_SIZE)));
}

vec2 deliotUnpackNoise(uint packedPair) {
    float t = (float(packedPair & 0xffffu) + 0.5) * (1.0 / 65536.0);
    t *= t;
    return vec2(t * t, float(int(packedPair) >> 16) * (1.0 / 4096.0));
}

// A 3D integer hash (PCG-style: one LCG step then cross-lane multiply-xor rounds) used to place spatial
// vertices of each virtual grid in the noise texture. Inputs are integer bit patterns (never uint(negative float)).
uvec3 deliotHash3(uvec3 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return v;
}

// log(1 - p), the per-light part of Eq. 16 (p is the same for every grid vertex and angular cell of a light).
// Series below p = 0.05: float log(1 - p) loses digits there (ports' (1 - p)^N loses everything below p ~ 1e-7).
float deliotLogMiss(float p) {
    return p < 0.05 ? -p * (1.0 + p * (0.5 + p * (1.0 / 3.0 + p * 0.25))) : log(max(1.0 - p, 0.0));
}

// Probability of at least one success in b(N, p), Eq. 16: P1 = 1 - (1 - p)^N = -expm1(N log(1 - p)), with a series
// where 1 - exp(e) cancels (e > -0.05): ~1e-6 relative accuracy for any p >= 1e-7. N < 1 (less than one facet on
// average) is a single trial of probability N p.
float deliotProbAtLeastOne(float N, float p, float logMiss) {
    if (N < 1.0) return clamp(N * p, 0.0, 1.0);
    float e = N * logMiss;   // <= 0; -inf when p == 1
    return e > -0.05 ? -e * (1.0 + e * (0.5 + e * (1.0 / 6.0 + e * (1.0 / 24.0)))) : 1.0 - exp(e);
}
float deliotProbAtLeastOne(float N, float p) { return deliotProbAtLeastOne(N, p, deliotLogMiss(p)); }

// Gated Gaussian approximation of a binomial draw b(N, p), Sec. 6.3, Eq. 16-18: a single Bernoulli trial with
// probability P1 decides whether any facet reflects; if so the count is 1 + a discretized Gaussian approximation of
// b(N - 1, p) (Eq. 17), clamped to [0, N - 1]. Two random numbers (u uniform in [0, 1), g standard normal), no loops.
// Eq. 18 prints the gate as H(theta0 - P1); the gate is open with probability P1, i.e. when theta0 < P1.
// Soft gate (the authors' supplemental code; Eq. 18 is the hard one): the gate is 1 - smoothstep(P1 - w, P1 + w, u)
// with half-width w = 0.1 sat(10 P1) sat(10 (1 - P1)). The step is symmetric about P1 and w <= min(P1, 1 - P1), so
// E[gate] = P1 exactly: the mean is kept, sparse regions show more pixels at partial intensity.
// Non-integer N is allowed (facet counts are expectations over a footprint): N < 1 gives 0 or 1.
// Split in two: the law's parameters (once per grid vertex and light) and the draw (once per angular cell), so
// the 4 angular draws of a vertex share one exp and one sqrt.
struct DeliotBinomialLaw {
    float P1;        // Eq. 16
    float mu;        // Eq. 17, Gaussian for b(N - 1, p)
    float sigma;
    float maxExtra;  // floor(N - 1): the count never exceeds N
    float gateHalf;  // half-width of the soft gate (0: Eq. 18's hard gate)
};

float deliotSoftGateHalfWidth(float P1) { return 0.1 * clamp(10.0 * P1, 0.0, 1.0) * clamp(10.0 * (1.0 - P1), 0.0, 1.0); }

DeliotBinomialLaw deliotBinomialLaw(float N, float p, float logMiss, bool softGate) {
    DeliotBinomialLaw law;
    bool none = !(N > 0.0) || !(p > 0.0);
    p = min(p, 1.0);
    float rest = max(N - 1.0, 0.0);
    law.P1 = none ? 0.0 : deliotProbAtLeastOne(N, p, logMiss);
    law.mu = rest * p;
    law.sigma = sqrt(rest * p * (1.0 - p));
    law.maxExtra = floor(rest);
    law.gateHalf = softGate ? deliotSoftGateHalfWidth(law.P1) : 0.0;
    return law;
}

float deliotDrawBinomial(DeliotBinomialLaw law, float u, float g) {
    float gate = law.gateHalf > 0.0 ? 1.0 - smoothstep(law.P1 - law.gateHalf, law.P1 + law.gateHalf, u)
                                    : (u < law.P1 ? 1.0 : 0.0);
    if (gate <= 0.0) return 0.0;
    return gate * (1.0 + clamp(floor(law.mu + law.sigma * g), 0.0, law.maxExtra));
}

float deliotGatedBinomial(float N, float p, float u, float g, bool softGate) {
    float pc = clamp(p, 0.0, 1.0);
    return deliotDrawBinomial(deliotBinomialLaw(N, p, deliotLogMiss(pc), softGate), u, g);
}
float deliotGatedBinomial(float N, float p, float u, float g) { return deliotGatedBinomial(N, p, u, g, false); }
