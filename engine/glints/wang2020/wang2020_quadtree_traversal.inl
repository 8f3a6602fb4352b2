// Template part of wang2020_quadtree.h: the CPU traversal of the particle tree (explicit reference).
#pragma once
#include <cmath>

namespace glimmer::wang2020 {

template <class Visit>
void forEachParticle(const Quadtree& tree, const Footprint& fp, float alpha, Visit visit) {
    glm::dvec2 lo = fp.aabbMin(), hi = fp.aabbMax();
    double cells = std::ldexp(1.0, tree.depth);
    int x0 = int(std::floor(lo.x * cells)), x1 = int(std::floor(hi.x * cells));
    int y0 = int(std::floor(lo.y * cells)), y1 = int(std::floor(hi.y * cells));
    // Descend from the root of every tile the footprint touches, only into non-empty nodes overlapping the AABB.
    struct Node {
        int level, x, y;
    };
    std::vector<Node> stack;
    for (int ty = int(std::floor(lo.y)); ty <= int(std::floor(hi.y)); ++ty)
        for (int tx = int(std::floor(lo.x)); tx <= int(std::floor(hi.x)); ++tx) stack.push_back({0, tx, ty});
    while (!stack.empty()) {
        Node n = stack.back();
        stack.pop_back();
        if (tree.count(n.level, n.x, n.y) == 0) continue;
        int shift = tree.depth - n.level;
        // Leaf-cell range of this node, against the AABB's.
        long nx0 = long(n.x) << shift, ny0 = long(n.y) << shift, span = long(1) << shift;
        if (nx0 + span - 1 < x0 || nx0 > x1 || ny0 + span - 1 < y0 || ny0 > y1) continue;
        if (n.level == tree.depth) {
            uint32_t c = tree.count(n.level, n.x, n.y);
            for (uint32_t k = 0; k < c; ++k) {
                Particle p = leafParticle(tree, n.x, n.y, k, alpha);
                if (fp.contains(p.uv)) visit(p);
            }
            continue;
        }
        for (int c = 0; c < 4; ++c) stack.push_back({n.level + 1, 2 * n.x + (c & 1), 2 * n.y + (c >> 1)});
    }
}

}  // namespace glimmer::wang2020
