#include "reference/discrete_facets/facet_realization.h"

#include <algorithm>
#include <bit>
#include <random>
#include <unordered_map>

namespace glimmer::facets {

namespace {
constexpr double kPi = 3.14159265358979323846;

// A uniform in (0, 1) from 32 bits (never 0 or 1, so logs and inverse CDFs stay finite).
double unit32(uint64_t bits) { return (double(bits & 0xffffffffull) + 0.5) * (1.0 / 4294967296.0); }
}  // namespace

// SplitMix64's finalizer (Steele, Lea & Flood 2014): a bijective 64-bit mixer, so distinct keys give distinct,
// well-spread outputs.
uint64_t FacetRealization::mix(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

FacetRealization::FacetRealization(const FacetMaterial& material) : material_(material) {
    const double density = material_.densityPerUv;
    tileSide_ = density > 0.0 && std::isfinite(density) ? std::sqrt(kTileMeanFacets / density) : 1.0;
    material_.anisotropy = std::max(1.0, material_.anisotropy);
    // The metric of the splits: a typical lobe query's extents in (u1, u2) (the lobe region of a half vector
    // alpha / 2 from the normal), and in UV the side of a square holding 64 expected facets of such a lobe
    // (measured: cheapest over 0.05 .. 30000 reflecting facets per footprint, with the exact whole-box count of
    // facet_estimator.cpp; 1 would favour sparse footprints, 1024 dense ones).
    const double theta = std::atan(0.5 * material_.alpha);
    FacetRegion lobe = lobeRegion({std::sin(theta), 0.0, std::cos(theta)});
    double du1 = std::max(lobe.u1Max - lobe.u1Min, 1e-9);
    double du2 = 0.0;
    for (int r = 0; r < lobe.azimuthRanges; ++r) du2 += lobe.u2Max[size_t(r)] - lobe.u2Min[size_t(r)];
    du2 = std::max(du2, 1e-9);
    // Facets in a tile x lobe box: kTileMeanFacets du1 du2; a UV square of side s (in tiles) holds 64 when
    // s^2 kTileMeanFacets du1 du2 = 64.
    const double side = 1.0 / std::sqrt(std::max(kTileMeanFacets * du1 * du2 / 64.0, 1.0));
    splitWeight_[0] = splitWeight_[1] = 1.0 / side;
    splitWeight_[2] = 1.0 / du1;
    splitWeight_[3] = 1.0 / du2;
}

uint64_t FacetRealization::tileKey(int64_t tx, int64_t ty) const {
    return mix(mix(mix(material_.seed ^ 0x5851f42d4c957f2dull) ^ uint64_t(tx)) ^ (uint64_t(ty) * 0xd1342543de82ef95ull));
}

uint32_t FacetRealization::tileCount(int64_t tx, int64_t ty) const {
    const double density = material_.densityPerUv;
    if (!(density > 0.0) || !std::isfinite(density)) return 0;
    uint64_t state = mix(tileKey(tx, ty) ^ 0x2545f4914f6cdd1dull);
    auto uniform = [&state] {
        state = mix(state);
        return unit32(state >> 16);
    };
    return poissonSample(kTileMeanFacets, uniform);
}

namespace {
// A UniformRandomBitGenerator over the hash stream of one key, for the standard library's distributions.
struct HashStream {
    using result_type = uint64_t;
    uint64_t state;
    static constexpr result_type min() { return 0; }
    static constexpr result_type max() { return ~uint64_t(0); }
    result_type operator()() { return state = FacetRealization::mix(state); }
};
}  // namespace

uint32_t FacetRealization::splitLeft(uint64_t key, uint32_t n) const {
    if (n > 1024) {   // exact rejection sampling in O(1) (libstdc++: Devroye 1986, Ch. X.4)
        // The top of every tile's tree is drawn again by every query that meets the tile: remembered per thread
        // (the draw is a function of key and n, so this only saves time; about 2 us a draw, 20 per query).
        thread_local std::unordered_map<uint64_t, uint32_t> drawn;
        const uint64_t id = mix(key ^ (uint64_t(n) * 0x9e3779b97f4a7c15ull));
        if (auto it = drawn.find(id); it != drawn.end()) return it->second;
        if (drawn.size() > (size_t(1) << 20)) drawn.clear();
        HashStream stream{key ^ 0x3c6ef372fe94f82bull};
        const uint32_t left = std::binomial_distribution<uint32_t>(n, 0.5)(stream);
        drawn.emplace(id, left);
        return left;
    }
    // Binomial(n, 1/2) exactly: the number of ones among n independent fair bits.
    uint32_t ones = 0;
    uint64_t word = key;
    for (uint32_t done = 0; done < n; done += 64) {
        word = mix(word + 0x7f4a7c159e3779b9ull);
        uint32_t take = std::min<uint32_t>(64, n - done);
        uint64_t bits = take == 64 ? word : (word & ((uint64_t(1) << take) - 1));
        ones += uint32_t(std::popcount(bits));
    }
    return ones;
}

void FacetRealization::leafPoint(const Node& node, uint32_t index, double p[4], double& hue) const {
    uint64_t r0 = mix(node.key ^ (uint64_t(index + 1) * 0xa0761d6478bd642full));
    uint64_t r1 = mix(r0 ^ 0xe7037ed1a0b428dbull);
    const double u[4] = {unit32(r0), unit32(r0 >> 32), unit32(r1), unit32(r1 >> 32)};
    for (int d = 0; d < 4; ++d) p[d] = node.lo[d] + (node.hi[d] - node.lo[d]) * u[d];
    hue = material_.colorVariation > 0.0 ? unit32(mix(r1 ^ 0x8ebc6af09c88c6e3ull)) : 0.0;
}

Facet FacetRealization::makeFacet(int64_t tx, int64_t ty, const double p[4], double hue) const {
    Facet f;
    f.uv = glm::dvec2((double(tx) + p[0]) * tileSide_, (double(ty) + p[1]) * tileSide_);
    f.m = normalFromUniforms(p[2], p[3]);
    f.color = material_.color;
    if (material_.colorVariation > 0.0)
        for (int k = 0; k < 3; ++k)
            f.color[k] *= 1.0 + material_.colorVariation * std::cos(2.0 * kPi * (hue + double(k) / 3.0));
    return f;
}

glm::dvec3 FacetRealization::normalFromUniforms(double u1, double u2) const {
    const double a2 = material_.alpha * material_.alpha;
    u1 = std::clamp(u1, 0.0, 1.0 - 1e-16);
    // Inverse CDF of the polar angle of D(m) (m.n): GGX tan^2 = a^2 u / (1 - u) (Walter et al. 2007, Eq. 35),
    // Beckmann tan^2 = -a^2 ln(1 - u) (Eq. 28).
    double tan2 = material_.ndf == kNdfBeckmann ? -a2 * std::log1p(-u1) : a2 * u1 / (1.0 - u1);
    double cosTheta = 1.0 / std::sqrt(1.0 + tan2), sinTheta = std::sqrt(tan2) * cosTheta;
    double phi = 2.0 * kPi * u2;
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

double FacetRealization::polarUniform(double theta) const {
    if (theta <= 0.0) return 0.0;
    if (theta >= 0.5 * kPi) return 1.0;
    const double a2 = material_.alpha * material_.alpha;
    double t = std::tan(theta), tan2 = t * t;
    return material_.ndf == kNdfBeckmann ? -std::expm1(-tan2 / a2) : tan2 / (a2 + tan2);
}

double FacetRealization::lobeRadius() const {
    // The lobe holds e = sin(angle) x stretch <= reach (facet_estimator.h LobeTest); stretch >= 1 / sqrt(a).
    const double stretch = std::sqrt(material_.anisotropy);
    const double reach = material_.lobe == Lobe::Cone ? std::sin(material_.gamma) : 4.0 * (material_.gamma / std::sqrt(2.0));
    return std::asin(std::min(1.0, reach * stretch));
}

FacetRegion FacetRealization::lobeRegion(const glm::dvec3& h, double extraRadius) const {
    FacetRegion region;
    const double radius = lobeRadius() + std::max(extraRadius, 0.0);
    if (radius >= kPi) return region;   // every normal (the default region's u1 and u2 ranges)
    const double theta = std::acos(std::clamp(h.z, -1.0, 1.0));
    const double margin = 1e-9;
    region.u1Min = std::max(0.0, polarUniform(theta - radius - margin) - 1e-12);
    region.u1Max = std::min(1.0, polarUniform(theta + radius + margin) + 1e-12);
    if (theta <= radius + margin || radius >= 0.5 * kPi) {   // the lobe holds the pole (or is that wide): every azimuth
        region.azimuthRanges = 1;
        region.u2Min[0] = 0.0;
        region.u2Max[0] = 1.0;
        return region;
    }
    // Largest azimuth offset of a point within `radius` of h on the sphere: asin(sin radius / sin theta).
    const double dphi = std::asin(std::min(1.0, std::sin(radius + margin) / std::sin(theta)));
    double centre = std::atan2(h.y, h.x) / (2.0 * kPi);
    if (centre < 0.0) centre += 1.0;
    const double half = dphi / (2.0 * kPi) + 1e-12;
    double lo = centre - half, hi = centre + half;
    if (half >= 0.5) {
        region.azimuthRanges = 1;
        region.u2Min[0] = 0.0;
        region.u2Max[0] = 1.0;
    } else if (lo < 0.0) {
        region.azimuthRanges = 2;
        region.u2Min = {0.0, lo + 1.0};
        region.u2Max = {hi, 1.0};
    } else if (hi > 1.0) {
        region.azimuthRanges = 2;
        region.u2Min = {lo, 0.0};
        region.u2Max = {1.0, hi - 1.0};
    } else {
        region.azimuthRanges = 1;
        region.u2Min[0] = lo;
        region.u2Max[0] = hi;
    }
    return region;
}

}  // namespace glimmer::facets
