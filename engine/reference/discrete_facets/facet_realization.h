// One fixed, deterministic realization of the glint material (README "The glint material"; ../shared/methods.md
// "The physical glint material"): a Poisson process of mirror facets on the UV plane whose normals follow
// D(m) (m.n) of the material's NDF. It is the ground truth every method is measured against (issue 36), in the
// manner of Jakob et al. 2014's discrete stochastic microfacets: each facet of the realization exists once, and a
// pixel counts the facets of its footprint whose normal reflects the half vector.
//
// The realization. Facets are points of a Poisson process of intensity `densityPerUv` in UV, each with a normal
// drawn from D(m) (m.n). Write the normal by the two uniforms (u1, u2) that the inverse CDF maps to it (u1 the
// polar angle through the NDF's marginal, u2 = phi / 2 pi): the facets are then a homogeneous Poisson process in
// the 4D space (u, v, u1, u2) of uniform intensity. The UV plane is cut into square tiles holding
// kTileMeanFacets facets on average (so the tile's side follows the density); each tile's count is Poisson, drawn
// from an integer hash of (seed, tile), and the tile's 4D box is halved recursively
// (the widest side under a fixed metric, see walk()), each half receiving Binomial(n, 1/2) of the parent's facets, until a box holds at most
// kLeafFacets; a leaf's facets are uniform in its box. Every count comes from a hash of the box's path (binomials
// of at most 1024 trials as the number of ones among n hashed bits; larger ones by libstdc++'s
// std::binomial_distribution, an exact rejection sampler, fed by the same hash stream), so the
// realization is the same whatever is asked of it and in whatever order: a sub-box of a homogeneous Poisson
// process is Poisson with the sub-box's mean and independent of the rest, so this draws exactly the process's law
// (no approximation anywhere; the counts are exact Poisson and binomial draws).
//
// Queries visit the boxes that meet a region of (u, v, u1, u2) and enumerate every facet in them: culling by the
// boxes' bounds is exact (a facet outside a box that misses the region cannot be in the region). A query's region
// is the footprint's UV bounding box times a box around the half vector in (u1, u2) that contains the whole
// reflection lobe; the caller then weighs each facet exactly (facet_reference.h).
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace glimmer::facets {

// The shape of one facet's reflection lobe around its normal m (the half vectors h it reflects):
//  Cone: h reflects when the angle between m and h is at most gamma (the README's definition; solid angle
//        2 pi (1 - cos gamma) ~ pi gamma^2).
//  Gaussian: weight exp(-sin^2(theta) / (2 sigma^2)) with sigma = gamma / sqrt(2), the same solid angle
//        (2 pi sigma^2 = pi gamma^2), truncated at sin(theta) = 4 sigma (mass outside 3e-4; the normalization
//        integrates the same truncated kernel, so the mean stays exact).
// Anisotropy a >= 1 stretches the lobe along the tangent: semi-axes about gamma sqrt(a) (tangent) and
// gamma / sqrt(a) (bitangent), equal solid angle (kemppinen2025's A* = diag(1 / sqrt a, sqrt a), Sec. 3.3.6); the
// exact shape is in facet_estimator.h (LobeTest).
enum class Lobe { Cone = 0, Gaussian = 1 };

constexpr int kNdfGgx = 0, kNdfBeckmann = 1;   // mirror NDF_GGX / NDF_BECKMANN (shaders/common/constants.glsl)

struct FacetMaterial {
    double densityPerUv = 2e6;   // facets per unit UV area (glint density x m^2 per unit UV x the scene's scale)
    double gamma = 0.015;        // half-angle of the reflection cone, radians
    double alpha = 0.3;          // base NDF roughness
    int ndf = kNdfGgx;
    double anisotropy = 1.0;     // >= 1, lobe stretch along the tangent
    glm::dvec3 color{1.0};       // glint tint
    double colorVariation = 0.0; // per-facet hue: c = color (1 + v cos(2 pi (hue + k / 3))), k = channel (mean: color)
    uint64_t seed = 0;           // realization; materials of one scene use their index
    Lobe lobe = Lobe::Cone;
};

// One facet: UV position, normal in the shading frame (z = surface normal, x = tangent), colour.
struct Facet {
    glm::dvec2 uv;
    glm::dvec3 m;
    glm::dvec3 color;
};

// A region of (u, v, u1, u2): a UV box and, in the normal's uniforms, a range of u1 and up to two ranges of u2
// (the azimuth wraps around).
struct FacetRegion {
    glm::dvec2 uvMin{0.0}, uvMax{0.0};
    double u1Min = 0.0, u1Max = 1.0;
    int azimuthRanges = 1;
    std::array<double, 2> u2Min{0.0, 0.0}, u2Max{1.0, 1.0};
};

// Mean facets per tile (the tile side follows the density). Large, so that a footprint meets few tiles whatever
// the density: the tree, not the tiling, narrows the search (the top splits draw large binomials in O(1)).
constexpr double kTileMeanFacets = 1048576.0;
constexpr uint32_t kLeafFacets = 4;          // a box with at most this many facets is not split further

class FacetRealization {
public:
    explicit FacetRealization(const FacetMaterial& material);

    const FacetMaterial& material() const { return material_; }
    double tileSide() const { return tileSide_; }

    // The normal that the uniforms (u1, u2) map to (inverse CDF of D(m) (m.n)), shading frame.
    glm::dvec3 normalFromUniforms(double u1, double u2) const;
    // The u1 of polar angle theta (the marginal CDF of the NDF's polar angle), theta in [0, pi/2].
    double polarUniform(double theta) const;
    // Half-width (radians) of a cone around h that contains the whole lobe of a facet reflecting h.
    double lobeRadius() const;
    // The region of normals that can reflect h (shading frame), as u1 / u2 ranges; UV box left empty. With
    // extraRadius > 0: that can reflect any half vector within extraRadius (radians) of h (an extended light).
    FacetRegion lobeRegion(const glm::dvec3& h, double extraRadius = 0.0) const;

    // Calls visit(const Facet&) for every facet of the realization inside `region` (exact; a facet on the
    // region's boundary is included). Facet colours are filled in. Thread-safe (no state changes).
    template <class Visit> void forEach(const FacetRegion& region, Visit&& visit) const;

    // forEach with whole boxes: `inner(uvLo, uvHi, u1Lo, u1Hi, u2Lo, u2Hi)` is asked about each box met (UV in
    // UV units; u1, u2 the normal's uniforms); when it returns true, the box's facets are not generated and
    // `count(n)` receives their number instead (exact: the box holds exactly n facets; for callers whose
    // weights are equal over such a box, e.g. a box footprint and a cone lobe that contain it entirely).
    template <class Visit, class Inner, class Count>
    void forEachOrCount(const FacetRegion& region, Visit&& visit, Inner&& inner, Count&& count) const;

    // Visits every facet of one tile (tests).
    template <class Visit> void forEachInTile(int64_t tx, int64_t ty, Visit&& visit) const;

    // Building blocks, exposed for the tests.
    static uint64_t mix(uint64_t x);
    uint32_t tileCount(int64_t tx, int64_t ty) const;

private:
    struct Node {
        uint64_t key;
        uint32_t count;
        int depth;
        double lo[4], hi[4];   // box in tile-normalized (x, y, u1, u2)
    };
    template <class Visit> void walk(int64_t tx, int64_t ty, const double qlo[4], const double qhi[4],
                                     Visit&& visit) const {
        walk(tx, ty, qlo, qhi, visit, [](const double*, const double*, const double*, const double*, const double*,
                                         const double*) { return false; },
             [](uint32_t) {});
    }
    template <class Visit, class Inner, class Count>
    void walk(int64_t tx, int64_t ty, const double qlo[4], const double qhi[4], Visit&& visit, Inner&& inner,
              Count&& count) const;
    uint32_t splitLeft(uint64_t key, uint32_t n) const;   // Binomial(n, 1/2)
    void leafPoint(const Node& node, uint32_t index, double p[4], double& hue) const;
    Facet makeFacet(int64_t tx, int64_t ty, const double p[4], double hue) const;
    uint64_t tileKey(int64_t tx, int64_t ty) const;

    FacetMaterial material_;
    double tileSide_ = 1.0;
    double splitWeight_[4] = {1.0, 1.0, 1.0, 1.0};   // per axis of (x, y, u1, u2): extent x weight picks the split
};

// Poisson(mean) from uniforms produced by `uniform()` (exact: inversion for small means, Hormann's PTRS
// transformed rejection for mean >= 10).
template <class Uniform> uint32_t poissonSample(double mean, Uniform&& uniform);

// ---- implementation of the templates ----

template <class Visit> void FacetRealization::forEach(const FacetRegion& region, Visit&& visit) const {
    const double side = tileSide_;
    int64_t tx0 = int64_t(std::floor(region.uvMin.x / side)), tx1 = int64_t(std::floor(region.uvMax.x / side));
    int64_t ty0 = int64_t(std::floor(region.uvMin.y / side)), ty1 = int64_t(std::floor(region.uvMax.y / side));
    for (int64_t ty = ty0; ty <= ty1; ++ty)
        for (int64_t tx = tx0; tx <= tx1; ++tx) {
            double qlo[4] = {region.uvMin.x / side - double(tx), region.uvMin.y / side - double(ty), region.u1Min, 0.0};
            double qhi[4] = {region.uvMax.x / side - double(tx), region.uvMax.y / side - double(ty), region.u1Max, 0.0};
            for (int r = 0; r < region.azimuthRanges; ++r) {
                qlo[3] = region.u2Min[size_t(r)];
                qhi[3] = region.u2Max[size_t(r)];
                walk(tx, ty, qlo, qhi, visit);
            }
        }
}

template <class Visit, class Inner, class Count>
void FacetRealization::forEachOrCount(const FacetRegion& region, Visit&& visit, Inner&& inner, Count&& count) const {
    const double side = tileSide_;
    int64_t tx0 = int64_t(std::floor(region.uvMin.x / side)), tx1 = int64_t(std::floor(region.uvMax.x / side));
    int64_t ty0 = int64_t(std::floor(region.uvMin.y / side)), ty1 = int64_t(std::floor(region.uvMax.y / side));
    for (int64_t ty = ty0; ty <= ty1; ++ty)
        for (int64_t tx = tx0; tx <= tx1; ++tx) {
            double qlo[4] = {region.uvMin.x / side - double(tx), region.uvMin.y / side - double(ty), region.u1Min, 0.0};
            double qhi[4] = {region.uvMax.x / side - double(tx), region.uvMax.y / side - double(ty), region.u1Max, 0.0};
            // A box inside the query is counted by the caller's test alone: the two azimuth ranges never both
            // hold a box (they are disjoint), so nothing is counted twice.
            auto innerUv = [&](const double* lo, const double* hi, const double* u1lo, const double* u1hi,
                               const double* u2lo, const double* u2hi) {
                double uvLo[2] = {(double(tx) + lo[0]) * side, (double(ty) + lo[1]) * side};
                double uvHi[2] = {(double(tx) + hi[0]) * side, (double(ty) + hi[1]) * side};
                return inner(uvLo, uvHi, u1lo, u1hi, u2lo, u2hi);
            };
            for (int r = 0; r < region.azimuthRanges; ++r) {
                qlo[3] = region.u2Min[size_t(r)];
                qhi[3] = region.u2Max[size_t(r)];
                walk(tx, ty, qlo, qhi, visit, innerUv, count);
            }
        }
}

template <class Visit> void FacetRealization::forEachInTile(int64_t tx, int64_t ty, Visit&& visit) const {
    const double qlo[4] = {0.0, 0.0, 0.0, 0.0}, qhi[4] = {1.0, 1.0, 1.0, 1.0};
    walk(tx, ty, qlo, qhi, visit);
}

template <class Visit, class Inner, class Count>
void FacetRealization::walk(int64_t tx, int64_t ty, const double qlo[4], const double qhi[4], Visit&& visit,
                            Inner&& inner, Count&& count) const {
    Node stack[160];
    int top = 0;
    Node root{tileKey(tx, ty), tileCount(tx, ty), 0, {0.0, 0.0, 0.0, 0.0}, {1.0, 1.0, 1.0, 1.0}};
    stack[top++] = root;
    while (top > 0) {
        Node node = stack[--top];

        if (node.count == 0) continue;
        bool meets = true;
        for (int d = 0; d < 4; ++d) meets = meets && node.lo[d] <= qhi[d] && node.hi[d] >= qlo[d];
        if (!meets) continue;
        // A box wholly inside the query box (every azimuth range but the one queried excludes it) whose facets
        // the caller weighs equally: counted without generating them.
        bool within = true;
        for (int d = 0; d < 4; ++d) within = within && node.lo[d] >= qlo[d] && node.hi[d] <= qhi[d];
        if (within && inner(&node.lo[0], &node.hi[0], &node.lo[2], &node.hi[2], &node.lo[3], &node.hi[3])) {
            count(node.count);
            continue;
        }
        if (node.count <= kLeafFacets || node.depth >= 62) {
            // Each facet is tested against the query box itself (not only its leaf), so a facet is reported by
            // exactly the queries whose box holds it, once per query even when two azimuth ranges meet its leaf.
            for (uint32_t i = 0; i < node.count; ++i) {
                double p[4], hue;
                leafPoint(node, i, p, hue);
                if (p[0] < qlo[0] || p[0] > qhi[0] || p[1] < qlo[1] || p[1] > qhi[1] || p[2] < qlo[2] ||
                    p[2] > qhi[2] || p[3] < qlo[3] || p[3] > qhi[3])
                    continue;
                visit(makeFacet(tx, ty, p, hue));
            }
            continue;
        }
        // Split the box's widest side under the material's metric (splitWeight_), so that boxes take the shape of
        // a typical light query (a footprint of about one expected reflecting facet times a lobe): a query then
        // meets few boxes whatever its footprint. The axis depends on the box alone, so the realization does not
        // depend on the queries.
        int axis = 0;
        double widest = -1.0;
        for (int d = 0; d < 4; ++d) {
            double extent = (node.hi[d] - node.lo[d]) * splitWeight_[d];
            if (extent > widest) widest = extent, axis = d;
        }
        const uint32_t left = splitLeft(node.key, node.count);
        const double middle = 0.5 * (node.lo[axis] + node.hi[axis]);
        Node a = node, b = node;
        a.depth = b.depth = node.depth + 1;
        a.key = mix(node.key * 2 + 0x632be59bd9b4e019ull);
        b.key = mix(node.key * 2 + 0x9e3779b97f4a7c15ull + 1);
        a.count = left;
        b.count = node.count - left;
        a.hi[axis] = middle;
        b.lo[axis] = middle;
        stack[top++] = b;
        stack[top++] = a;
    }
}

template <class Uniform> uint32_t poissonSample(double mean, Uniform&& uniform) {
    if (!(mean > 0.0)) return 0;
    if (mean < 10.0) {   // inversion: the CDF summed term by term
        double u = uniform(), p = std::exp(-mean), cdf = p;
        uint32_t k = 0;
        while (u > cdf && k < 1000) {
            ++k;
            p *= mean / double(k);
            cdf += p;
        }
        return k;
    }
    // PTRS (W. Hormann, "The transformed rejection method for generating Poisson random variables", 1993).
    const double s = std::sqrt(mean), lm = std::log(mean);
    const double b = 0.931 + 2.53 * s, a = -0.059 + 0.02483 * b;
    const double invAlpha = 1.1239 + 1.1328 / (b - 3.4), vr = 0.9277 - 3.6224 / (b - 2.0);
    for (;;) {
        double u = uniform() - 0.5, v = uniform();
        double us = 0.5 - std::abs(u);
        double k = std::floor((2.0 * a / us + b) * u + mean + 0.43);
        if (us >= 0.07 && v <= vr) return uint32_t(k);
        if (k < 0.0 || (us < 0.013 && v > us)) continue;
        if (std::log(v) + std::log(invAlpha) - std::log(a / (us * us) + b) <= -mean + k * lm - std::lgamma(k + 1.0))
            return uint32_t(k);
    }
}

}  // namespace glimmer::facets
