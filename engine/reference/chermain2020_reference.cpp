#include "reference/chermain2020_reference.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace glimmer::chermain2020 {

namespace {

constexpr float kPi = 3.14159265358979f;

struct Level {
    int level = 0;
    float log4n = 0.0f;
    glm::vec2 st{0.0f};
    float A = 0.0f, B = 0.0f, C = 0.0f;
    int row0 = 0, row1 = -1;
    bool allSmooth = false;
};

struct Footprint {
    bool noFootprint = false, noFacets = false;
    float blend = 0.0f;
    Level levels[2];
};

Level setupLevel(const ReferenceParams& p, int level, glm::vec2 st, glm::vec2 d0, glm::vec2 d1, float log4n0,
                 int levels) {
    Level lv;
    lv.level = level;
    lv.log4n = log4n0 + float(level);
    float cellsPerUnit = std::exp2(float(levels - 1 - level));
    lv.st = st * cellsPerUnit - 0.5f;
    d0 *= cellsPerUnit;
    d1 *= cellsPerUnit;
    float A = d0.y * d0.y + d1.y * d1.y + 1.0f, B = -2.0f * (d0.x * d0.y + d1.x * d1.y),
          C = d0.x * d0.x + d1.x * d1.x + 1.0f;
    float invF = 1.0f / (A * C - 0.25f * B * B);
    lv.A = A * invF;
    lv.B = B * invF;
    lv.C = C * invF;
    float det = 4.0f * lv.A * lv.C - lv.B * lv.B;
    float halfHeight = 2.0f * std::sqrt(lv.A * det) / det;
    lv.row0 = int(std::ceil(lv.st.y - halfHeight));
    lv.row1 = int(std::floor(lv.st.y + halfHeight));
    lv.allSmooth = lv.log4n - p.densityRandomization * 5.4f >= float(levels) - 0.5f && p.relativeArea >= 1.0f;
    return lv;
}

Footprint setupFootprint(const ReferenceParams& p, glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy, int levels,
                         float densityScale) {
    Footprint f;
    glm::vec2 stretch(1.0f, std::max(p.glintAnisotropy, 1.0f));
    glm::vec2 st = uv * stretch, d0 = duvdx * stretch, d1 = duvdy * stretch;
    if (glm::dot(d0, d0) < glm::dot(d1, d1)) std::swap(d0, d1);
    float major = glm::length(d0), minor = glm::length(d1);
    if (minor * p.maxAnisotropy < major && minor > 0.0f) {
        float k = major / (minor * p.maxAnisotropy);
        d1 *= k;
        minor *= k;
    }
    f.noFacets = !(densityScale > 0.0f);
    f.noFootprint = !(minor > 0.0f) || std::isinf(minor);
    float l = std::clamp(float(levels - 1) + std::log2(std::max(minor, 1e-30f)) + p.lodBias, 0.0f, 100.0f);
    int il = int(std::floor(l));
    f.blend = l - float(il);
    float lnN0 = p.logDensity + std::log(std::max(densityScale, 1e-30f)) - std::log(stretch.y) -
                 2.0f * float(levels - 1) * 0.69314718f;
    float log4n0 = lnN0 / 1.38629436f;
    f.levels[0] = setupLevel(p, il, st, d0, d1, log4n0, levels);
    f.levels[1] = setupLevel(p, il + 1, st, d0, d1, log4n0, levels);
    return f;
}

// Visits the cells of a level's ellipse in the shader's order with their EWA weights.
template <class Visit>
void forEachCell(const Level& lv, Visit visit) {
    const float edge = std::exp(-2.0f);
    int cells = 0;
    for (int it = lv.row0; it <= lv.row1 && cells < 128; ++it) {
        float tt = float(it) - lv.st.y;
        float disc = lv.B * lv.B * tt * tt - 4.0f * lv.A * (lv.C * tt * tt - 1.0f);
        if (disc <= 0.0f) continue;
        float root = std::sqrt(disc);
        int s0 = int(std::ceil(lv.st.x + (-lv.B * tt - root) / (2.0f * lv.A)));
        int s1 = int(std::floor(lv.st.x + (-lv.B * tt + root) / (2.0f * lv.A)));
        for (int is = s0; is <= s1 && cells < 128; ++is) {
            float ss = float(is) - lv.st.x;
            float r2 = lv.A * ss * ss + lv.B * ss * tt + lv.C * tt * tt;
            if (r2 >= 1.0f) continue;
            visit(glm::ivec2(is, it), double(std::exp(-2.0f * r2) - edge));
            ++cells;
        }
    }
}

// The table as the GPU reads it at normalized coordinate t (mirrored repeat, linear between texel centres).
double marginalAt(const Dictionary& d, int level, int m, float t) {
    const int res = d.spec.resolution;
    float u = t * float(res) - 0.5f;
    int j0 = int(std::floor(u));
    float f = u - float(j0);
    auto at = [&](int k) {
        k = k < 0 ? -k - 1 : k;
        k = k % (2 * res);
        k = k >= res ? 2 * res - 1 - k : k;
        return double(d.at(level, m, k));
    };
    return (1.0 - f) * at(j0) + f * at(j0 + 1);
}

double targetP22(glm::vec2 m, glm::vec3 shape, int ndf) {
    double sx = shape.x, sy = shape.y, rho = shape.z, c = 1.0 - rho * rho;
    double q = (m.x * m.x / (sx * sx) - 2.0 * rho * m.x * m.y / (sx * sy) + m.y * m.y / (sy * sy)) / c;
    double norm = 1.0 / (2.0 * M_PI * sx * sy * std::sqrt(c));
    if (ndf == 1) return norm * std::exp(-0.5 * q);
    double t = 1.0 + 0.5 * q;
    return norm / (t * t);
}

}  // namespace

std::array<uint32_t, 4> hash4(std::array<uint32_t, 4> v) {
    for (uint32_t& x : v) x = x * 1664525u + 1013904223u;
    auto mix = [&] {
        v[0] += v[1] * v[3];
        v[1] += v[2] * v[0];
        v[2] += v[0] * v[1];
        v[3] += v[1] * v[2];
    };
    mix();
    for (uint32_t& x : v) x ^= x >> 16u;
    mix();
    return v;
}

float probit(float p) {
    const float plow = 0.02425f;
    if (p < plow || p > 1.0f - plow) {
        float q = std::sqrt(-2.0f * std::log(p < plow ? p : 1.0f - p));
        float x = (((((-7.784894002430293e-03f * q - 3.223964580411365e-01f) * q - 2.400758277161838e+00f) * q -
                     2.549732539343734e+00f) * q + 4.374664141464968e+00f) * q + 2.938163982698783e+00f) /
                  ((((7.784695709041462e-03f * q + 3.224671290700398e-01f) * q + 2.445134137142996e+00f) * q +
                    3.754408661907416e+00f) * q + 1.0f);
        return p < plow ? x : -x;
    }
    float q = p - 0.5f, r = q * q;
    return (((((-3.969683028665376e+01f * r + 2.209460984245205e+02f) * r - 2.759285104469687e+02f) * r +
              1.383577518672690e+02f) * r - 3.066479806614716e+01f) * r + 2.506628277459239e+00f) * q /
           (((((-5.447609879822406e+01f * r + 1.615858368580409e+02f) * r - 1.556989798598866e+02f) * r +
              6.680131188771972e+01f) * r - 1.328068155288572e+01f) * r + 1.0f);
}

CellDraw drawCell(const ReferenceParams& p, int level, glm::ivec2 cell, float log4n, int levels) {
    CellDraw draw;
    uint32_t shift = uint32_t(std::min(level, 31));
    uint32_t seedBits;
    std::memcpy(&seedBits, &p.seed, sizeof seedBits);
    std::array<uint32_t, 4> r = hash4({uint32_t(cell.x) << shift, uint32_t(cell.y) << shift, seedBits, 0x9e3779b9u});
    float uArea = (float(r[0] & 0xffffu) + 0.5f) * (1.0f / 65536.0f);
    draw.empty = uArea > p.relativeArea;
    float uDensity = (float(r[1] >> 8u) + 0.5f) * (1.0f / 16777216.0f);
    float lf = log4n + p.densityRandomization * probit(uDensity);
    if (p.lobeCount > 0.5f && lf < 0.0f) {   // lobe_count = material: kept with probability 4^lf, weighted 1 / 4^lf
        float keep = std::exp2(2.0f * lf);
        draw.empty = draw.empty || (float(r[3] >> 8u) + 0.5f) * (1.0f / 16777216.0f) > keep;
        draw.scale = 1.0f / keep;
    }
    draw.dictionaryLevel = int(std::clamp(std::round(lf), 0.0f, float(levels)));
    draw.theta = 2.0f * kPi * (float(r[0] >> 16u) + 0.5f) * (1.0f / 65536.0f);
    draw.marginalX = int(((r[2] & 0xffffu) * 192u) >> 16u);
    draw.marginalY = int(((r[2] >> 16u) * 192u) >> 16u);
    return draw;
}

std::vector<WeightedCell> footprintCells(const ReferenceParams& p, glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy,
                                         int levels, float densityScale) {
    Footprint f = setupFootprint(p, uv, duvdx, duvdy, levels, densityScale);
    std::vector<WeightedCell> cells;
    double total = 0.0;
    const Level& lv = f.levels[0];
    forEachCell(lv, [&](glm::ivec2 c, double w) {
        cells.push_back({c, w, drawCell(p, lv.level, c, lv.log4n, levels)});
        total += w;
    });
    for (WeightedCell& c : cells) c.weight /= total;
    return cells;
}

double referenceD(const Dictionary& d, const ReferenceParams& p, glm::vec2 uv, glm::vec2 duvdx, glm::vec2 duvdy,
                  glm::vec3 h, float alpha, int ndf, float densityScale) {
    const int levels = d.spec.levels;
    h = glm::normalize(h);
    Footprint f = setupFootprint(p, uv, duvdx, duvdy, levels, densityScale);
    if (h.z <= 0.0f || f.noFacets) return 0.0;
    glm::vec2 m = -glm::vec2(h.x, h.y) / h.z;
    double cos4 = double(h.z) * h.z * h.z * h.z;
    float ratio = std::sqrt(std::max(p.roughnessAnisotropy, 1e-3f));
    float sx = std::clamp(alpha * ratio * 0.70710678f, 0.005f, 1.0f), sy = std::clamp(alpha / ratio * 0.70710678f, 0.005f, 1.0f);
    float rho = std::clamp(p.slopeCorrelation, -0.99f, 0.99f);
    glm::vec3 shape(sx, sy, rho);
    double smooth = targetP22(m, shape, ndf);
    if (f.noFootprint) return smooth / cos4;
    if (p.lobeCount > 0.5f && p.glintAngle > 0.0f) {   // lobe_count = material: (s / sigma_lobe)^2 of the lobes
        const float sd = float(d.spec.sigmaDict()), lobe = float(d.spec.lobeStd);
        float sd2 = 0.5f * p.glintAngle * p.glintAngle * sd * sd / (sx * sy * std::sqrt(1.0f - rho * rho));
        float thin = std::min(0.0f, std::log(sd2 / (lobe * lobe)) / 1.38629436f);
        for (Level& lv : f.levels) {
            lv.log4n += thin;
            lv.allSmooth = lv.log4n - p.densityRandomization * 5.4f >= float(levels) - 0.5f && p.relativeArea >= 1.0f;
        }
    }
    float c = std::sqrt(1.0f - rho * rho);
    glm::mat2 W(1.0f / (sx * c), 0.0f, -rho / (sy * c), 1.0f / sy);
    glm::vec2 u = W * m;
    double detT = 1.0;
    if (ndf != 1) {
        float r2 = glm::dot(u, u), q = 1.0f + 0.5f * r2;
        float scale = r2 > 1e-8f ? std::sqrt(2.0f * std::log(q) / r2) : 1.0f;
        u *= scale;
        detT = 1.0 / q;
    }
    const double sigmaDict = d.spec.sigmaDict(), range = d.spec.range();
    const double jacobian = sigmaDict * sigmaDict * std::abs(glm::determinant(W)) * detT;
    auto levelP22 = [&](const Level& lv) {
        if (lv.allSmooth) return smooth;
        double sum = 0.0, weights = 0.0;
        forEachCell(lv, [&](glm::ivec2 cell, double w) {
            weights += w;
            CellDraw draw = drawCell(p, lv.level, cell, lv.log4n, levels);
            if (draw.empty) return;
            if (draw.dictionaryLevel == levels) {
                sum += w * smooth;
                return;
            }
            float ct = std::cos(draw.theta), sn = std::sin(draw.theta);
            glm::vec2 o = float(sigmaDict) * (glm::mat2(ct, -sn, sn, ct) * u);
            glm::vec2 a = glm::abs(o);
            if (a.x >= range || a.y >= range) return;
            sum += w * draw.scale * marginalAt(d, draw.dictionaryLevel, draw.marginalX, float(a.x / range)) *
                   marginalAt(d, draw.dictionaryLevel, draw.marginalY, float(a.y / range)) * jacobian;
        });
        return weights > 0.0 ? sum / weights : 0.0;
    };
    double P = 0.0;
    if (f.blend < 1.0f) P += (1.0 - f.blend) * levelP22(f.levels[0]);
    if (f.blend > 0.0f) P += f.blend * levelP22(f.levels[1]);
    return std::max(P, 0.0) / cos4;
}

}  // namespace glimmer::chermain2020
