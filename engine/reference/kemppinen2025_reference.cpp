#include "reference/kemppinen2025_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "glints/methods.h"

namespace glimmer::kemppinen2025 {

static constexpr double kPi = 3.14159265358979323846;
static constexpr double kKappa = 3.0;      // KEMPPINEN_KAPPA in kemppinen2025.glsl
static constexpr double kMaxLevel = 24.0;

Params paramsFrom(const ParamValues& values) {
    const GlintMethod& method = findGlintMethod("kemppinen2025");
    auto get = [&](const char* name) {
        for (const ParamSpec& spec : method.params)
            if (spec.name == name) return double(paramOr(values, spec));
        return 0.0;
    };
    Params p;
    p.density = get("density");
    p.microRoughness = get("micro_roughness");
    p.filterSize = get("filter_size");
    p.neighbors = get("neighbors") > 0.5 ? 16 : 4;
    p.glintAnisotropy = get("glint_anisotropy");
    p.roughnessAnisotropy = get("roughness_anisotropy");
    p.colorVariation = get("color_variation");
    p.triplanar = get("triplanar") > 0.5;
    p.piCovariance = get("angular_covariance") < 0.5;
    p.authorsLod = get("lod") < 0.5;
    return p;
}

double glintWidthScale(const Params& params) { return params.piCovariance ? std::sqrt(kPi) : 1.0; }

glm::dvec2 splitAlpha(double alpha, double roughnessAnisotropy) {
    double r = std::sqrt(roughnessAnisotropy);
    return glm::max(glm::dvec2(alpha * r, alpha / r), glm::dvec2(1e-4));
}

double smoothD(const glm::dvec3& h, const glm::dvec2& alpha, int ndf) {
    if (h.z <= 0.0) return 0.0;
    if (ndf == kBeckmann) {
        glm::dvec2 s = glm::dvec2(h.x, h.y) / (h.z * alpha);
        double c2 = h.z * h.z;
        return std::exp(-glm::dot(s, s)) / (kPi * alpha.x * alpha.y * c2 * c2);
    }
    glm::dvec3 v(h.x / alpha.x, h.y / alpha.y, h.z);
    double l2 = glm::dot(v, v);
    return 1.0 / (kPi * alpha.x * alpha.y * l2 * l2);
}

glm::dvec2 toPrior(const glm::dvec3& h, const glm::dvec2& alpha, int ndf) {
    glm::dvec2 p;
    if (ndf == kBeckmann) {
        // B2^-1 (slope) then B1^-1 (Marsaglia's polar map backwards), Sec. 3.2.2.
        glm::dvec2 s = glm::dvec2(h.x, h.y) / (std::max(h.z, 1e-7) * alpha);
        double s2 = glm::dot(s, s);
        p = s2 > 0.0 ? s * std::sqrt(-std::expm1(-s2) / s2) : s;
    } else {
        // M~ then Lambert's equal-area projection L(x, y, z) = (x, y) / sqrt(1 + z), Eq. 6-7.
        glm::dvec3 w = glm::normalize(glm::dvec3(h.x / alpha.x, h.y / alpha.y, std::max(h.z, 0.0)));
        p = glm::dvec2(w.x, w.y) / std::sqrt(1.0 + w.z);
    }
    return 0.5 + 0.5 * p;
}

glm::dvec3 fromPrior(const glm::dvec2& x, const glm::dvec2& alpha, int ndf) {
    glm::dvec2 p = 2.0 * x - 1.0;
    double r2 = std::min(glm::dot(p, p), 1.0);
    if (ndf == kBeckmann) {
        r2 = std::min(r2, 1.0 - 1e-12);
        double ratio = r2 > 0.0 ? -std::log1p(-r2) / r2 : 1.0;
        glm::dvec2 slope = p * std::sqrt(ratio) * alpha;
        return glm::normalize(glm::dvec3(slope, 1.0));
    }
    glm::dvec3 w(p * std::sqrt(2.0 - r2), 1.0 - r2);
    return glm::normalize(glm::dvec3(w.x * alpha.x, w.y * alpha.y, w.z));
}

// The 4D hash of kemppinen2025_core.glsl (PCG-style, Jarzynski & Olano's construction), 32-bit wrap-around.
static glm::uvec4 hash4(glm::uvec4 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
    v ^= v >> 16u;
    v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
    return v;
}

static glm::uvec4 cellHash(glm::ivec2 s, glm::ivec2 a, int level, int process) {
    glm::uvec4 key(uint32_t(s.x), uint32_t(s.y), uint32_t(a.x), uint32_t(a.y));
    key ^= glm::uvec4(uint32_t(level) * 0x9E3779B9u, uint32_t(process) * 0x85EBCA6Bu,
                      uint32_t(level) * 0xC2B2AE35u, uint32_t(process + 1) * 0x27D4EB2Fu);
    return hash4(key);
}

GridPoint gridPoint(glm::ivec2 s, glm::ivec2 a, int level, int process) {
    glm::uvec4 h = cellHash(s, a, level, process);
    const double inv16 = 1.0 / 65536.0;
    return {glm::dvec2(h.x >> 16u, h.y >> 16u) * inv16, glm::dvec2(h.z >> 16u, h.w >> 16u) * inv16,
            double(h.x & 0xFFFFu) * inv16, double(h.y & 0xFFFFu) * inv16};
}

static double smoothstep(double e0, double e1, double x) {
    double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

double roulette(double r, double w) {
    const double eps = 0.1;
    return smoothstep(std::max(0.0, r - eps), std::min(1.0, r + eps), w);
}

glm::dvec3 glintColor(double hue, double variation) {
    return 1.0 + variation * glm::dvec3(std::cos(2.0 * kPi * hue), std::cos(2.0 * kPi * (hue + 1.0 / 3.0)),
                                        std::cos(2.0 * kPi * (hue + 2.0 / 3.0)));
}

double intervalMass(double x, double sigma, double lo, double hi) {
    if (hi <= lo) return 0.0;
    double s = 1.0 / (std::sqrt(2.0) * sigma);
    return 0.5 * (std::erf((hi - x) * s) - std::erf((lo - x) * s));
}

static Process makeProcess(glm::dvec2 uv, glm::dvec2 dx, glm::dvec2 dy, glm::dvec2 stretch, double resolution,
                           double filterSize, bool authorsLod, double weight) {
    Process p;
    p.weight = weight;
    p.xs = stretch * uv;
    glm::dvec2 jx = stretch * dx, jy = stretch * dy;
    double f2 = filterSize * filterSize, floorVar = 1e-8 / (resolution * resolution);
    double a = f2 * (jx.x * jx.x + jy.x * jy.x) + floorVar;
    double b = f2 * (jx.x * jx.y + jy.x * jy.y);
    double c = f2 * (jx.y * jx.y + jy.y * jy.y) + floorVar;
    p.covariance = glm::dmat2(a, b, b, c);
    double mean = 0.5 * (a + c), diff = 0.5 * (a - c);
    double major = std::sqrt(mean + std::sqrt(diff * diff + b * b));
    double lambda = authorsLod ? std::log2(filterSize * std::max(glm::length(jx), glm::length(jy)) * resolution) +
                                     std::exp2(filterSize)
                               : std::log2(2.0 * kKappa * major * resolution);
    p.lambda = std::clamp(lambda, 0.0, kMaxLevel);
    return p;
}

PixelSetup setupPixel(const Params& params, const Surface& s) {
    PixelSetup px;
    double density = params.density * s.densityScale;
    px.hasGlints = density > 0.0;
    px.density = std::max(density, 1e-6);
    px.resolution = std::sqrt(px.density);
    px.alpha = splitAlpha(s.alpha, params.roughnessAnisotropy);
    double an = std::sqrt(params.glintAnisotropy);
    glm::dvec2 stretch = params.triplanar ? glm::dvec2(1.0) : glm::dvec2(1.0 / an, an);
    px.angularStretch = 1.0 / stretch;
    if (!params.triplanar) {
        px.processCount = 1;
        px.process[0] =
            makeProcess(s.uv, s.duvdx, s.duvdy, stretch, px.resolution, params.filterSize, params.authorsLod, 1.0);
    } else {
        px.processCount = 3;
        glm::dvec3 w = glm::abs(s.normal);
        w /= std::max(w.x + w.y + w.z, 1e-6);
        auto plane = [](const glm::dvec3& v, int q) {
            return q == 0 ? glm::dvec2(v.y, v.z) : q == 1 ? glm::dvec2(v.x, v.z) : glm::dvec2(v.x, v.y);
        };
        for (int q = 0; q < 3; ++q)
            px.process[q] = makeProcess(plane(s.position, q), plane(s.dPdx, q), plane(s.dPdy, q), stretch,
                                        px.resolution, params.filterSize, params.authorsLod, w[q]);
    }
    return px;
}

glm::dvec3 filteredNdf(const Params& params, const PixelSetup& px, int ndf, const glm::dvec3& h, int* count) {
    if (!px.hasGlints || h.z <= 0.0) return glm::dvec3(0.0);
    double d = smoothD(h, px.alpha, ndf);
    if (d < 1e-20) return glm::dvec3(0.0);   // as in the shader: D underflows there in float
    glm::dvec2 xa = toPrior(h, px.alpha, ndf);
    glm::dvec2 sigmaA = params.microRoughness * glintWidthScale(params) * std::sqrt(d) * px.angularStretch;
    // The angular grid lives in x_a' = x_a / A*^-1, where the lobe is isotropic (kemppinen2025.glsl).
    glm::dvec2 extent = 1.0 / px.angularStretch;
    glm::dvec2 xaPrime = xa * extent;
    double sigmaIso = params.microRoughness * glintWidthScale(params) * std::sqrt(d);
    double angularNorm = 1.0 / (2.0 * kPi * sigmaA.x * sigmaA.y);
    double squareMass = intervalMass(xa.x, sigmaA.x, 0.0, 1.0) * intervalMass(xa.y, sigmaA.y, 0.0, 1.0);
    int side = params.neighbors == 16 ? 4 : 2;
    double blockOffset = 0.5 * side - 0.5;
    glm::dvec3 explicitSum(0.0);
    double compensation = 0.0;
    for (int q = 0; q < px.processCount; ++q) {
        const Process& proc = px.process[q];
        glm::dmat2 invCov = glm::inverse(proc.covariance);
        double spatialNorm = 1.0 / (2.0 * kPi * std::sqrt(glm::determinant(proc.covariance)));
        int level0 = int(std::floor(proc.lambda));
        double frac = proc.lambda - level0;
        glm::dvec3 processSum(0.0);
        for (int li = 0; li < 2; ++li) {
            int level = level0 + li;
            double w = (li == 0 ? 1.0 - frac : frac) * proc.weight;
            double resS = px.resolution * std::exp2(-level), resA = std::exp2(level);
            glm::ivec2 a0 = glm::ivec2(glm::floor(xaPrime * resA - blockOffset));
            glm::ivec2 cellsA = glm::ivec2(glm::ceil(extent * resA));
            glm::ivec2 s0 = glm::ivec2(glm::floor(proc.xs * resS - 0.5));
            glm::dvec2 lo = glm::max(glm::dvec2(a0) / resA, glm::dvec2(0.0));
            glm::dvec2 hi = glm::min(glm::dvec2(a0 + side) / resA, extent);
            double blockMass = intervalMass(xaPrime.x, sigmaIso, lo.x, hi.x) * intervalMass(xaPrime.y, sigmaIso, lo.y, hi.y);
            compensation += w * std::max(squareMass - blockMass, 0.0);
            for (int ai = 0; ai < side * side; ++ai) {
                glm::ivec2 cellA = a0 + glm::ivec2(ai % side, ai / side);
                bool valid = cellA.x >= 0 && cellA.y >= 0 && cellA.x < cellsA.x && cellA.y < cellsA.y;
                for (int si = 0; si < 4; ++si) {
                    glm::ivec2 cellS = s0 + glm::ivec2(si & 1, si >> 1);
                    if (count) ++*count;
                    if (!valid) continue;
                    GridPoint p = gridPoint(cellS, cellA, level, q);
                    glm::dvec2 ga = (glm::dvec2(cellA) + p.angular) / (resA * extent);
                    glm::dvec2 gs = (glm::dvec2(cellS) + p.spatial) / resS;
                    if (glm::dot(ga - 0.5, ga - 0.5) >= 0.25) continue;
                    glm::dvec2 ds = proc.xs - gs, da = xa - ga;
                    double e = glm::dot(ds, invCov * ds) + da.x * da.x / (sigmaA.x * sigmaA.x) +
                               da.y * da.y / (sigmaA.y * sigmaA.y);
                    processSum += roulette(p.roulette, w) * std::exp(-0.5 * e) * glintColor(p.hue, params.colorVariation);
                }
            }
        }
        explicitSum += processSum * spatialNorm;
    }
    return d * (explicitSum * (angularNorm / px.density) + glm::dvec3(compensation));
}

glm::dvec3 filteredNdf(const Params& params, const Surface& surface, const glm::dvec3& h, int* count) {
    return filteredNdf(params, setupPixel(params, surface), surface.ndf, h, count);
}

}  // namespace glimmer::kemppinen2025

namespace glimmer::kemppinen2025 {

SamplerRng::SamplerRng(uint32_t seed) : state(seed * 747796405u + 2891336453u) {}

double SamplerRng::next() {
    // PCG-RXS-M-XS 32 (O'Neill), the same steps as kemppinenRandom in the shader.
    state = state * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    word = (word >> 22u) ^ word;
    return double(word >> 8) * (1.0 / 16777216.0);
}

double priorJacobian(const glm::dvec3& h, const glm::dvec2& alpha, int ndf) {
    if (h.z <= 0.0) return 0.0;
    if (ndf == kBeckmann) return kPi * smoothD(h, alpha, ndf) * h.z / 4.0;
    double v = glm::length(glm::dvec3(h.x / alpha.x, h.y / alpha.y, h.z));
    return 1.0 / (8.0 * alpha.x * alpha.y * v * v * v);
}

glm::dvec3 sampleSmoothNdfCos(const glm::dvec2& alpha, int ndf, double u1, double u2) {
    // D(h) h.z dw = P22(slope) d(slope), and the slope distributions of GGX and Beckmann are stretch-invariant:
    // draw the unit-roughness slope radius (Walter et al. 2007, Eq. 28 / 35 with alpha = 1), stretch by alpha.
    double tan2 = ndf == kBeckmann ? -std::log(std::max(1.0 - u1, 1e-12)) : u1 / std::max(1.0 - u1, 1e-12);
    double phi = 2.0 * kPi * u2, r = std::sqrt(tan2);
    return glm::normalize(glm::dvec3(r * std::cos(phi) * alpha.x, r * std::sin(phi) * alpha.y, 1.0));
}

double defensivePriorPdf(const glm::dvec2& xa, const glm::dvec2& alpha, int ndf) {
    // D(h) h.z / |J_T(h)|: 4 / pi for Beckmann (T carries D cos to the uniform disk), 8 h.z / (pi |M^T h|) for GGX.
    if (glm::dot(xa - 0.5, xa - 0.5) >= 0.25) return 0.0;
    if (ndf == kBeckmann) return 4.0 / kPi;
    glm::dvec3 h = fromPrior(xa, alpha, ndf);
    double v = glm::length(glm::dvec3(h.x / alpha.x, h.y / alpha.y, h.z));
    return 8.0 * h.z / (kPi * v);
}

double defensiveProbability(const Params& params, const PixelSetup& px, int ndf, int level) {
    int side = params.neighbors == 16 ? 4 : 2;
    double sigma = params.microRoughness * glintWidthScale(params) * std::sqrt(smoothD(glm::dvec3(0, 0, 1), px.alpha, ndf));
    double inside = std::erf(side * std::exp2(-level) / (2.0 * std::sqrt(2.0) * sigma));
    return std::max(0.1, 1.0 - inside * inside);
}

namespace {

// One explicit term of a block (Algorithm 2 lines 11-12), in the stretched angular space x_a'.
struct SampleTerm {
    glm::dvec2 centre;   // g_a'
    double sigma;        // alpha* sqrt(D(T^-1(g_a)))
    double weight;       // R N_s Luminance(c) (without the block mass)
};

struct BlockGeometry {
    glm::dvec2 lo, hi;   // B clipped to the stretched square
};

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// The terms of the block with lower-left angular cell a0 at `level` of process q. Points outside U, outside
// the grid or with zero weight are left out.
int blockTerms(const Params& params, const PixelSetup& px, int ndf, int q, int level, double levelWeight,
               glm::ivec2 a0, SampleTerm* terms, BlockGeometry& geometry) {
    const Process& proc = px.process[q];
    int side = params.neighbors == 16 ? 4 : 2;
    glm::dvec2 extent = 1.0 / px.angularStretch;
    double resA = std::exp2(level), resS = px.resolution * std::exp2(-level);
    glm::ivec2 cellsA = glm::ivec2(glm::ceil(extent * resA));
    glm::ivec2 s0 = glm::ivec2(glm::floor(proc.xs * resS - 0.5));
    glm::dmat2 invCov = glm::inverse(proc.covariance);
    geometry.lo = glm::max(glm::dvec2(a0) / resA, glm::dvec2(0.0));
    geometry.hi = glm::min(glm::dvec2(a0 + side) / resA, extent);
    int count = 0;
    for (int ai = 0; ai < side * side; ++ai) {
        glm::ivec2 cellA = a0 + glm::ivec2(ai % side, ai / side);
        if (cellA.x < 0 || cellA.y < 0 || cellA.x >= cellsA.x || cellA.y >= cellsA.y) continue;
        for (int si = 0; si < 4; ++si) {
            glm::ivec2 cellS = s0 + glm::ivec2(si & 1, si >> 1);
            GridPoint p = gridPoint(cellS, cellA, level, q);
            glm::dvec2 centre = (glm::dvec2(cellA) + p.angular) / resA;
            glm::dvec2 ga = centre / extent;
            if (glm::dot(ga - 0.5, ga - 0.5) >= 0.25) continue;
            glm::dvec2 ds = proc.xs - (glm::dvec2(cellS) + p.spatial) / resS;
            // A term whose spatial Gaussian is below e^-50 is absent, as in the shader: float underflows where
            // double does not, and the reservoir draws one number per present term, so both must agree on which
            // terms exist for the CPU twin to follow the shader's random stream sample by sample.
            double exponent = glm::dot(ds, invCov * ds);
            double spatial = exponent < 100.0 ? std::exp(-0.5 * exponent) : 0.0;
            double w = roulette(p.roulette, levelWeight) * spatial * luminance(glintColor(p.hue, params.colorVariation));
            if (!(w > 0.0)) continue;
            double d = smoothD(fromPrior(ga, px.alpha, ndf), px.alpha, ndf);
            if (d < 1e-20) continue;
            terms[count++] = {centre, params.microRoughness * glintWidthScale(params) * std::sqrt(d), w};
        }
    }
    return count;
}

double termMass(const SampleTerm& t, const BlockGeometry& b) {
    return intervalMass(t.centre.x, t.sigma, b.lo.x, b.hi.x) * intervalMass(t.centre.y, t.sigma, b.lo.y, b.hi.y);
}

// Truncated normal on [lo, hi] by inverting the CDF (an interval entirely above the mean is mirrored below it,
// where erf differences keep more precision).
double sampleTruncatedNormal(double mean, double sigma, double lo, double hi, double u) {
    double a = (lo - mean) / (std::sqrt(2.0) * sigma), b = (hi - mean) / (std::sqrt(2.0) * sigma);
    bool mirrored = a > 0.0;
    if (mirrored) {
        std::swap(a, b);
        a = -a;
        b = -b;
    }
    double ea = std::erf(a), eb = std::erf(b);
    double target = ea + u * (eb - ea);
    // erf^-1 by bisection (Newton from a tail start diverges where erf is flat); erf is 1 beyond |x| = 6.
    double left = std::max(a, -6.0), right = std::min(b, 6.0);
    if (left > right) return mean + std::sqrt(2.0) * sigma * (mirrored ? -0.5 * (a + b) : 0.5 * (a + b));
    for (int i = 0; i < 64; ++i) {
        double mid = 0.5 * (left + right);
        if (std::erf(mid) < target) left = mid; else right = mid;
    }
    double x = 0.5 * (left + right);
    if (mirrored) x = -x;
    return mean + std::sqrt(2.0) * sigma * x;
}

}  // namespace

HalfVectorSample sampleHalfVector(const Params& params, const PixelSetup& px, int ndf, SamplerRng& rng) {
    HalfVectorSample out;
    if (!px.hasGlints) return out;
    // Process by triplanar weight, level by the roulette of lines 4-6.
    int q = 0;
    double u = rng.next(), acc = 0.0;
    for (int i = 0; i < px.processCount; ++i) {
        acc += px.process[i].weight;
        if (u < acc || i == px.processCount - 1) {
            q = i;
            break;
        }
    }
    const Process& proc = px.process[q];
    int level0 = int(std::floor(proc.lambda));
    double frac = proc.lambda - level0;
    int level = rng.next() < frac ? level0 + 1 : level0;
    double levelWeight = (level == level0 ? 1.0 - frac : frac) * proc.weight;
    glm::dvec2 extent = 1.0 / px.angularStretch;
    glm::dvec2 xPrime;
    if (rng.next() < defensiveProbability(params, px, ndf, level)) {
        // Defensive branch: the smooth NDF's D(h) h.z (for Beckmann the same as uniform in U).
        double u1 = rng.next(), u2 = rng.next();
        xPrime = toPrior(sampleSmoothNdfCos(px.alpha, ndf, u1, u2), px.alpha, ndf) * extent;
    } else {
        int side = params.neighbors == 16 ? 4 : 2;
        double resA = std::exp2(level);
        // Braces: list-initialisation evaluates left to right, as GLSL does (parentheses leave C++ the order).
        glm::dvec2 xa = glm::dvec2{rng.next(), rng.next()} * extent;   // line 2 (over the square)
        glm::ivec2 a0 = glm::ivec2(glm::floor(xa * resA - (0.5 * side - 0.5)));
        SampleTerm terms[64];
        BlockGeometry block;
        int n = blockTerms(params, px, ndf, q, level, levelWeight, a0, terms, block);
        double total = 0.0;
        int chosen = -1;
        for (int i = 0; i < n; ++i) {   // lines 9-15: reservoir sampling, one uniform per term
            double w = terms[i].weight * termMass(terms[i], block);
            total += w;
            double r = rng.next();
            if (w > 0.0 && r < w / total) chosen = i;
        }
        if (chosen < 0) {
            // Empty block: uniform inside it (kept in the pdf).
            xPrime = block.lo + glm::dvec2{rng.next(), rng.next()} * (block.hi - block.lo);
        } else {
            const SampleTerm& t = terms[chosen];
            xPrime = {sampleTruncatedNormal(t.centre.x, t.sigma, block.lo.x, block.hi.x, rng.next()),
                      sampleTruncatedNormal(t.centre.y, t.sigma, block.lo.y, block.hi.y, rng.next())};
        }
    }
    out.prior = xPrime / extent;
    if (glm::dot(out.prior - 0.5, out.prior - 0.5) >= 0.25) return out;   // outside U: no direction
    out.h = fromPrior(out.prior, px.alpha, ndf);
    out.pdf = samplePriorPdf(params, px, ndf, out.prior) * priorJacobian(out.h, px.alpha, ndf);
    return out;
}

double samplePriorPdf(const Params& params, const PixelSetup& px, int ndf, const glm::dvec2& xa) {
    if (!px.hasGlints || glm::dot(xa - 0.5, xa - 0.5) >= 0.25) return 0.0;
    int side = params.neighbors == 16 ? 4 : 2;
    glm::dvec2 extent = 1.0 / px.angularStretch;
    glm::dvec2 xPrime = xa * extent;
    double pdf = 0.0;
    for (int q = 0; q < px.processCount; ++q) {
        const Process& proc = px.process[q];
        int level0 = int(std::floor(proc.lambda));
        double frac = proc.lambda - level0;
        for (int li = 0; li < 2; ++li) {
            int level = level0 + li;
            double pLevel = li == 0 ? 1.0 - frac : frac;
            if (pLevel <= 0.0) continue;
            double levelWeight = pLevel * proc.weight;
            double rho = defensiveProbability(params, px, ndf, level);
            double p = rho * defensivePriorPdf(xa, px.alpha, ndf);
            double resA = std::exp2(level);
            glm::ivec2 cell = glm::ivec2(glm::floor(xPrime * resA));
            double offset = 0.5 * side - 0.5;
            for (int by = 0; by < side; ++by)
                for (int bx = 0; bx < side; ++bx) {
                    glm::ivec2 a0 = cell - glm::ivec2(bx, by);
                    // Probability that x_a (uniform over the square) selects this block.
                    glm::dvec2 lo = glm::max((glm::dvec2(a0) + offset) / resA, glm::dvec2(0.0));
                    glm::dvec2 hi = glm::min((glm::dvec2(a0) + offset + 1.0) / resA, extent);
                    if (hi.x <= lo.x || hi.y <= lo.y) continue;
                    double pBlock = (hi.x - lo.x) * (hi.y - lo.y);
                    SampleTerm terms[64];
                    BlockGeometry block;
                    int n = blockTerms(params, px, ndf, q, level, levelWeight, a0, terms, block);
                    double total = 0.0, density = 0.0;
                    for (int i = 0; i < n; ++i) {
                        total += terms[i].weight * termMass(terms[i], block);
                        glm::dvec2 d = xPrime - terms[i].centre;
                        double s2 = terms[i].sigma * terms[i].sigma;
                        density += terms[i].weight * std::exp(-0.5 * glm::dot(d, d) / s2) / (2.0 * kPi * s2);
                    }
                    double pInBlock = total > 0.0 ? density / total
                                                  : 1.0 / ((block.hi.x - block.lo.x) * (block.hi.y - block.lo.y));
                    p += (1.0 - rho) * pBlock * pInBlock;
                }
            pdf += proc.weight * pLevel * p;
        }
    }
    return pdf;
}

double sampleSolidAnglePdf(const Params& params, const PixelSetup& px, int ndf, const glm::dvec3& h) {
    if (h.z <= 0.0) return 0.0;
    return samplePriorPdf(params, px, ndf, toPrior(h, px.alpha, ndf)) * priorJacobian(h, px.alpha, ndf);
}

}  // namespace glimmer::kemppinen2025
