#include "glints/wang2020/wang2020_quadtree.h"

#include <algorithm>
#include <bit>
#include <random>
#include <thread>

#include "core/clock.h"
#include "core/error.h"
#include "core/log.h"
#include "glints/wang2020/wang2020_dpf.h"

namespace glimmer::wang2020 {

namespace {

// Multinomial split of n into four equally likely children: two nested binomial halvings (x, then y).
template <class Rng>
void splitFour(uint32_t n, Rng& rng, uint32_t out[4]) {
    auto half = [&](uint32_t m) -> uint32_t {
        if (m == 0) return 0;
        if (m <= 32) {
            // Binomial(m, 1/2) exactly: the number of set bits among m fair random bits.
            uint32_t bits = uint32_t(rng());
            return uint32_t(std::popcount(m == 32 ? bits : bits & ((1u << m) - 1u)));
        }
        std::binomial_distribution<uint32_t> b(m, 0.5);
        return b(rng);
    };
    uint32_t left = half(n), right = n - left;
    out[0] = half(left);      // (0, 0)
    out[2] = left - out[0];   // (0, 1)
    out[1] = half(right);     // (1, 0)
    out[3] = right - out[1];  // (1, 1)
}

// Splits the node at (level, x, y) into its children at level + 1.
template <class Rng>
void splitNode(Quadtree& t, int level, int x, int y, Rng& rng) {
    uint32_t n = t.counts[Quadtree::levelOffset(level) + (size_t(y) << level) + size_t(x)];
    uint32_t child[4];
    splitFour(n, rng, child);
    size_t base = Quadtree::levelOffset(level + 1);
    for (int c = 0; c < 4; ++c)
        t.counts[base + (size_t(2 * y + (c >> 1)) << (level + 1)) + size_t(2 * x + (c & 1))] = child[c];
}

}  // namespace

Quadtree buildQuadtree(double particles, int depth, uint32_t seed, int threads) {
    if (depth < 2 || depth > 13)
        throw UsageError("wang2020: quadtree depth " + std::to_string(depth) + " outside [2, 13]");
    if (!(particles >= 1.0 && particles <= 4e9))
        throw UsageError("wang2020: particle count " + std::to_string(particles) + " outside [1, 4e9]");
    Stopwatch clock;
    Quadtree t;
    t.depth = depth;
    t.particles = particles;
    t.counts.assign(Quadtree::levelOffset(depth + 1), 0u);
    t.counts[0] = uint32_t(std::llround(particles));
    std::mt19937 top(seed);
    for (int level = 0; level < 2; ++level)
        for (int y = 0; y < (1 << level); ++y)
            for (int x = 0; x < (1 << level); ++x) splitNode(t, level, x, y, top);
    // 16 level-2 subtrees, each with its own random stream: the result does not depend on the thread count.
    int workers = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (int w = 0; w < workers; ++w)
        pool.emplace_back([&, w] {
            for (int sub = w; sub < 16; sub += workers) {
                int sx = sub & 3, sy = sub >> 2;
                std::mt19937 rng(pcgHash(seed ^ pcgHash(uint32_t(sub) + 1u)));
                for (int level = 2; level < depth; ++level) {
                    int span = 1 << (level - 2);
                    for (int y = sy * span; y < (sy + 1) * span; ++y)
                        for (int x = sx * span; x < (sx + 1) * span; ++x) splitNode(t, level, x, y, rng);
                }
            }
        });
    for (std::thread& th : pool) th.join();
    t.buildMs = clock.elapsedMs();
    log::debug("wang2020: quadtree depth ", depth, ", N ", particles, ": ", t.bytes() / (1024.0 * 1024.0), " MB in ",
               t.buildMs, " ms");
    return t;
}

std::vector<uint32_t> shaderNodeWords(const Quadtree& tree) {
    std::vector<uint32_t> words = tree.counts;
    if (!words.empty() && words[0] >= kChildMask)
        throw UsageError("wang2020: " + std::to_string(words[0]) + " particles per tile do not fit the shader's tree");
    // Bottom-up, so that each child's word is final when its parent reads it: a leaf with one particle points at
    // itself; a parent with one particle has exactly one child with one particle and points where it points.
    size_t leaves = Quadtree::levelOffset(tree.depth);
    for (size_t i = leaves; i < words.size(); ++i)
        if (words[i] == 1u) words[i] = kSingleParticle;
    for (int level = tree.depth - 1; level >= 0; --level) {
        size_t base = Quadtree::levelOffset(level), childBase = Quadtree::levelOffset(level + 1);
        int shift = tree.depth - level - 1;   // bits of a child's relative leaf coordinates
        for (int y = 0; y < (1 << level); ++y)
            for (int x = 0; x < (1 << level); ++x) {
                uint32_t& word = words[base + (size_t(y) << level) + size_t(x)];
                uint32_t count = word, single = 0u, mask = 0u;
                for (uint32_t c = 0; c < 4; ++c) {
                    int cx = 2 * x + int(c & 1u), cy = 2 * y + int(c >> 1);
                    uint32_t child = words[childBase + (size_t(cy) << (level + 1)) + size_t(cx)];
                    if (child == 0u) continue;
                    mask |= 1u << c;
                    uint32_t rx = ((c & 1u) << shift) + (child & 0x1FFFu);
                    uint32_t ry = ((c >> 1) << shift) + ((child >> 13) & 0x1FFFu);
                    single = kSingleParticle | (ry << 13) | rx;   // used when count is 1 (one child, itself single)
                }
                if (count == 1u)
                    word = single;
                else if (count != 0u && count < (1u << 26))
                    word = kChildMask | (mask << 26) | count;
            }
    }
    return words;
}

Particle leafParticle(const Quadtree& tree, int x, int y, uint32_t k, float alpha) {
    int mask = (1 << tree.depth) - 1;
    uint32_t leafId = (uint32_t(y & mask) << tree.depth) | uint32_t(x & mask);
    Particle p;
    double cell = std::ldexp(1.0, -tree.depth);
    p.uv = glm::dvec2((x + double(hashUnit(leafId, k, 0))) * cell, (y + double(hashUnit(leafId, k, 1))) * cell);
    p.lambda = hashUnit(leafId, k, 2);
    // Beckmann normal with pdf D(m)(m.n): tan^2 theta = -alpha^2 ln(1 - u1), phi = 2 pi u2 (explicit reference).
    float u1 = hashUnit(leafId, k, 3), u2 = hashUnit(leafId, k, 4);
    float tan2 = -alpha * alpha * std::log(1.0f - u1);
    float cosT = 1.0f / std::sqrt(1.0f + tan2), sinT = std::sqrt(std::max(0.0f, 1.0f - cosT * cosT));
    float phi = 2.0f * kPi * u2;
    p.normal = glm::vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
    return p;
}

bool Footprint::contains(glm::dvec2 p) const {
    double det = duvdx.x * duvdy.y - duvdx.y * duvdy.x;
    if (std::abs(det) < 1e-30) return false;
    glm::dvec2 d = p - center;
    double s = (d.x * duvdy.y - d.y * duvdy.x) / det;
    double t = (duvdx.x * d.y - duvdx.y * d.x) / det;
    return std::abs(s) <= 0.5 && std::abs(t) <= 0.5;
}

}  // namespace glimmer::wang2020
