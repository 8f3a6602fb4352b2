#include "reference/deliot2023_reference.h"


#include <algorithm>
#include <cmath>

namespace glimmer::deliot2023 {

NoisePair unpackNoisePair(uint32_t packed) {
    float t = (float(packed & 0xffffu) + 0.5f) * (1.0f / 65536.0f);
    t *= t;
    return {t * t, float(int32_t(packed) >> 16) * (1.0f / 4096.0f)};
}

float probAtLeastOne(float N, float p) {
    if (N < 1.0f) return std::clamp(N * p, 0.0f, 1.0f);
    float logMiss = p < 0.05f ? -p * (1.0f + p * (0.5f + p * (1.0f / 3.0f + p * 0.25f))) : std::log(std::max(1.0f - p, 0.0f));
    float e = N * logMiss;
    return e > -0.05f ? -e * (1.0f + e * (0.5f + e * (1.0f / 6.0f + e * (1.0f / 24.0f)))) : 1.0f - std::exp(e);
}

float softGateHalfWidth(float P1) {
    return 0.1f * std::clamp(10.0f * P1, 0.0f, 1.0f) * std::clamp(10.0f * (1.0f - P1), 0.0f, 1.0f);
}

static float smoothstep(float e0, float e1, float x) {
    float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

float gatedBinomial(float N, float p, float u, float g, bool softGate) {
    if (!(N > 0.0f) || !(p > 0.0f)) return 0.0f;
    p = std::min(p, 1.0f);
    float P1 = probAtLeastOne(N, p);
    float half = softGate ? softGateHalfWidth(P1) : 0.0f;
    float gate = half > 0.0f ? 1.0f - smoothstep(P1 - half, P1 + half, u) : (u < P1 ? 1.0f : 0.0f);
    if (gate <= 0.0f) return 0.0f;
    float rest = std::max(N - 1.0f, 0.0f);
    float mu = rest * p;
    float sigma = std::sqrt(rest * p * (1.0f - p));
    return gate * (1.0f + std::clamp(std::floor(mu + sigma * g), 0.0f, std::floor(rest)));
}

Moments exactBinomialMoments(double N, double p) {
    Moments m;
    if (N < 1.0) {
        double q = N * p;
        return {q, q * (1.0 - q), 1.0 - q};
    }
    m.mean = N * p;
    m.variance = N * p * (1.0 - p);
    m.pZero = p >= 1.0 ? 0.0 : std::exp(N * std::log1p(-p));
    return m;
}

double orientationStep(int ratioLevel) { return 1.5707963267948966 * std::exp2(-double(ratioLevel)); }

GridSelection selectGrids(double major, double minor, double phi, double screenScale) {
    constexpr int kMaxRatioLevel = 16;
    constexpr double kPi = 3.141592653589793;
    GridSelection sel;
    major = std::max(major, 1e-20);
    minor = std::max(minor, major * std::exp2(-double(kMaxRatioLevel)));
    sel.ratio = major / minor;
    sel.lod = std::clamp(std::log2(minor * screenScale), -100.0, 100.0);
    double lod0 = std::floor(sel.lod);
    double scaleT = (std::exp2(2.0 * (sel.lod - lod0)) - 1.0) / 3.0;
    int k0 = std::clamp(int(std::floor(std::log2(sel.ratio))), 0, kMaxRatioLevel - 1);
    double ratio0 = std::exp2(double(k0));
    double ratioT = std::clamp((sel.ratio - ratio0) / ratio0, 0.0, 1.0);
    phi = std::fmod(phi, kPi);
    if (phi < 0.0) phi += kPi;
    sel.phi = phi;
    double pos = phi / orientationStep(k0);
    int o0 = int(std::floor(pos));
    double x = std::clamp(pos - o0, 0.0, 1.0), y = ratioT;
    struct V { int level, orientation; };
    V A{k0, o0}, B{k0, o0 + 1}, C{k0 + 1, 2 * o0}, M{k0 + 1, 2 * o0 + 1}, E{k0 + 1, 2 * o0 + 2};
    std::array<V, 3> tri;
    std::array<double, 3> b;
    if (k0 == 0) {   // one isotropic grid at level 0: a fan (see the shader)
        if (x < 0.5) {
            tri = {A, C, M};
            b = {1.0 - y, y * (1.0 - 2.0 * x), y * 2.0 * x};
        } else {
            tri = {A, M, E};
            b = {1.0 - y, y * (2.0 - 2.0 * x), y * (2.0 * x - 1.0)};
        }
    } else if (x <= 0.5 * y) {
        tri = {A, C, M};
        b = {1.0 - y, y - 2.0 * x, 2.0 * x};
    } else if (x >= 1.0 - 0.5 * y) {
        tri = {B, M, E};
        b = {1.0 - y, 2.0 * (1.0 - x), y - 2.0 * (1.0 - x)};
    } else {
        tri = {A, B, M};
        b = {0.0, x - 0.5 * y, y};
        b[0] = 1.0 - b[1] - b[2];
    }
    for (double& v : b) v = std::max(v, 0.0);
    std::array<double, 3> up, lo;
    up[0] = std::min(scaleT, b[0]);
    up[1] = std::clamp(scaleT - up[0], 0.0, b[1]);
    up[2] = std::clamp(scaleT - up[0] - up[1], 0.0, b[2]);
    for (int j = 0; j < 3; ++j) lo[j] = std::max(b[j] - up[j], 0.0);
    int tet = scaleT <= b[0] ? 0 : (scaleT <= b[0] + b[1] ? 1 : 2);
    int lodLo = int(lod0), lodHi = lodLo + 1;
    auto grid = [&](int v, int lod, double w) { return Grid{lod, tri[v].level, tri[v].orientation, w}; };
    if (tet == 0) sel.grids = {grid(0, lodLo, lo[0]), grid(1, lodLo, lo[1]), grid(2, lodLo, lo[2]), grid(0, lodHi, up[0])};
    else if (tet == 1) sel.grids = {grid(1, lodLo, lo[1]), grid(2, lodLo, lo[2]), grid(0, lodHi, up[0]), grid(1, lodHi, up[1])};
    else sel.grids = {grid(2, lodLo, lo[2]), grid(0, lodHi, up[0]), grid(1, lodHi, up[1]), grid(2, lodHi, up[2])};
    return sel;
}

}  // namespace glimmer::deliot2023
