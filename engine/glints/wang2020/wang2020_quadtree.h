// Wang et al. 2020, Sec. 4.4 "Spatial Tree Construction": the particles' spatial hierarchy, built by multinomial
// splitting of the particle count into the four children (Jakob et al. 2014). N particles per unit UV square; the
// square tiles the UV plane. Deviation from the paper's node buffer (two float4 per node: id, count, depth,
// child count, AABB): the tree is complete and implicit, one uint count per node stored level by level like a
// mip pyramid (node id, depth and AABB follow from the index), 4 bytes instead of 32 per node.
// Particles inside a leaf are procedural: particle k of leaf (x, y) has position, acceptance variable lambda
// (Eq. 7) and, for the explicit reference, a Beckmann normal, all from integer hashes shared with the GLSL
// (shaders/glints/wang2020/wang2020.glsl), so the CPU reference and the shader see the same particles.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace glimmer::wang2020 {

struct Quadtree {
    int depth = 0;                 // leaves at level `depth` (2^depth x 2^depth cells)
    double particles = 0;          // N per unit UV square
    std::vector<uint32_t> counts;  // level l starts at levelOffset(l); row-major 2^l x 2^l
    double buildMs = 0.0;

    static size_t levelOffset(int level) { return ((size_t(1) << (2 * level)) - 1) / 3; }
    uint32_t count(int level, int x, int y) const {  // x, y wrapped into the tile
        int mask = (1 << level) - 1;
        return counts[levelOffset(level) + (size_t(y & mask) << level) + size_t(x & mask)];
    }
    size_t bytes() const { return counts.size() * sizeof(uint32_t); }
};

// Builds the tree with `threads` std::threads (0: hardware concurrency); deterministic for a seed whatever the
// thread count (one random stream per level-2 subtree).
Quadtree buildQuadtree(double particles, int depth, uint32_t seed, int threads = 0);

// The tree as the shader reads it (shaders/glints/wang2020/wang2020.glsl), one uint per node in `counts`' order:
// - a node holding exactly one particle: kSingleParticle | the particle's leaf relative to the node (x in bits 0-12,
//   y in bits 13-25). At the default N a leaf holds 0.01-0.03 particles, so a thin footprint meets many such nodes:
//   the shader reaches the particle in one step instead of descending a chain of single children with three empty
//   siblings at every level.
// - an inner node with fewer than 2^26 particles: kChildMask | which children hold particles (bit c for child
//   c = x + 2 y, bits 26-29) | the count (bits 0-25): the shader pushes only those children.
// - otherwise the plain count (leaves, and inner nodes so full that all four children hold particles).
// Ours: the paper's nodes store counts and AABBs. Counts must stay below 2^30 (N is at most 1e9; UsageError).
inline constexpr uint32_t kSingleParticle = 0x80000000u;
inline constexpr uint32_t kChildMask = 0x40000000u;
std::vector<uint32_t> shaderNodeWords(const Quadtree& tree);

// Integer hash shared with GLSL (PCG output permutation).
inline uint32_t pcgHash(uint32_t v) {
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
// Uniform [0, 1) from 24 hash bits (exact in float on both sides).
inline float hashUnit(uint32_t leafId, uint32_t particle, uint32_t channel) {
    uint32_t h = pcgHash(pcgHash(leafId) + particle * 8u + channel);
    return float(h >> 8) * (1.0f / 16777216.0f);
}

struct Particle {
    glm::dvec2 uv;     // unwrapped UV position
    float lambda;      // Eq. 7 threshold variable
    glm::vec3 normal;  // Beckmann sample (explicit reference only), pdf D(m)(m.n)
};
// Particle k of the leaf at unwrapped cell (x, y).
Particle leafParticle(const Quadtree& tree, int x, int y, uint32_t k, float alpha);

// The pixel footprint in UV: the parallelogram uv + s duvdx + t duvdy, s, t in [-1/2, 1/2] (the pixel square
// mapped by the UV Jacobian).
struct Footprint {
    glm::dvec2 center, duvdx, duvdy;
    double area() const { return std::abs(duvdx.x * duvdy.y - duvdx.y * duvdy.x); }
    bool contains(glm::dvec2 p) const;
    glm::dvec2 aabbMin() const { return center - 0.5 * (glm::abs(duvdx) + glm::abs(duvdy)); }
    glm::dvec2 aabbMax() const { return center + 0.5 * (glm::abs(duvdx) + glm::abs(duvdy)); }
};

// Calls visit(particle) for every particle of the tree inside the footprint (full traversal to the leaves).
template <class Visit>
void forEachParticle(const Quadtree& tree, const Footprint& fp, float alpha, Visit visit);

}  // namespace glimmer::wang2020

#include "glints/wang2020/wang2020_quadtree_traversal.inl"
