// Kneiphof & Klein 2025, "Real-time Image-based Lighting of Glints" (EGSR 2025, CGF 44(4); arXiv 2507.02674), Sec. 4.2:
// the facets of a grid vertex of deliot2023 are shared among K radiance levels of the environment by a multinomial
// draw, made hierarchically by count-conserving binomial splits (K = 4: {0 1 | 2 3}, then {0 | 1} and {2 | 3};
// K = 8: {0-3 | 4-7} first). Included by glints/deliot2023.glsl; the statistics tests compile it too.
//
// The split: n facets (real, Eq. 10's distributed trials) go right with probability q each. Our reading of the
// paper's "dual-gated" Gaussian binomial: gates for the outcomes a Gaussian cannot place, all facets left
// ((1 - q)^n), exactly one right (n q (1 - q)^(n - 1)), exactly one left (n q^(n - 1) (1 - q)) and all right (q^n);
// otherwise the right count is a Gaussian of the binomial's variance n q (1 - q) around the exact conditional mean
// of the rest, (n q - P(1) - (n - 1) P(n - 1) - n P(n)) / P(rest), clamped to [2, n - 2]. Below 3 facets the gates
// are all left, all right, or the conditional mean of the rest; below 2, all or nothing (all right with probability
// q). The expectation is n q up to the clamp of the Gaussian tail; the left count is n minus the right one, so the
// levels' counts always sum to n (tests/environment_glints_test.cpp checks both).

// One split's probability and its logarithms, the same for every grid vertex of a pixel (kk25Tree).
struct Kk25Node {
    float q, logHit, logMiss;   // q, log q, log(1 - q)
};

Kk25Node kk25Node(float q) {
    q = clamp(q, 0.0, 1.0);
    return Kk25Node(q, log(max(q, 1e-30)), deliotLogMiss(q));
}

// Right count of the split (u uniform, g standard normal: one pair of deliot2023's noise). (1 - q)^(n - 1) and
// q^(n - 1) come from the "all" gates' powers: two exponentials per split.
float kk25Split(float n, Kk25Node node, float u, float g) {
    float q = node.q;
    if (!(n > 0.0) || q <= 0.0) return 0.0;
    if (q >= 1.0) return n;
    if (n < 2.0) return u < q ? n : 0.0;
    // Many facets on both sides (n min(q, 1 - q) > 30): every gate below e^-30, so the conditional mean of the rest
    // is n q to float precision and the gates' two exponentials are skipped (most splits of a dense footprint).
    if (n * min(q, 1.0 - q) > 30.0) return clamp(n * q + sqrt(n * q * (1.0 - q)) * g, 2.0, n - 2.0);
    float allLeft = exp(n * node.logMiss), allRight = exp(n * node.logHit);
    float oneRight = n >= 3.0 ? n * q * allLeft / (1.0 - q) : 0.0;
    float oneLeft = n >= 3.0 ? n * (1.0 - q) * allRight / q : 0.0;
    if (u < allLeft) return 0.0;
    if (u < allLeft + oneRight) return 1.0;
    if (u >= 1.0 - allRight) return n;
    if (u >= 1.0 - allRight - oneLeft) return n - 1.0;
    float rest = max(1.0 - allLeft - oneRight - oneLeft - allRight, 1e-12);
    float mean = clamp((n * q - oneRight - (n - 1.0) * oneLeft - n * allRight) / rest, 1.0, n - 1.0);
    if (n < 4.0) return mean;   // no room for a Gaussian between the gates
    return clamp(mean + sqrt(n * q * (1.0 - q)) * g, 2.0, n - 2.0);
}

// The split tree of K levels with probabilities p[i] (summing to 1), once per pixel. Its nodes, in the order they
// split: 6 = {0-3 | 4-7} (K = 8 only), then per group g of four 3g = {ab | cd}, 3g + 1 = {a | b}, 3g + 2 = {c | d};
// node k's q is the probability of its right side given the node.
struct Kk25Tree {
    Kk25Node node[7];
    int levels;
};

Kk25Tree kk25Tree(float p[8], int levels) {
    Kk25Tree tree;
    tree.levels = levels;
    for (int g = 0; g < 2; ++g) {
        float pa = p[4 * g], pb = p[4 * g + 1], pc = p[4 * g + 2], pd = p[4 * g + 3];
        tree.node[3 * g] = kk25Node((pc + pd) / max(pa + pb + pc + pd, 1e-30));
        tree.node[3 * g + 1] = kk25Node(pb / max(pa + pb, 1e-30));
        tree.node[3 * g + 2] = kk25Node(pd / max(pc + pd, 1e-30));
    }
    float lowGroup = p[0] + p[1] + p[2] + p[3], highGroup = p[4] + p[5] + p[6] + p[7];
    tree.node[6] = kk25Node(highGroup / max(lowGroup + highGroup, 1e-30));
    return tree;
}

// One group of four levels {a b | c d}: node `top` splits it, then `left` {a | b} and `right` {c | d}.
vec4 kk25Group(float n, Kk25Node top, Kk25Node left, Kk25Node right, vec2 rndTop, vec2 rndLeft, vec2 rndRight) {
    float cd = kk25Split(n, top, rndTop.x, rndTop.y);
    float ab = n - cd;
    float b = kk25Split(ab, left, rndLeft.x, rndLeft.y);
    float d = kk25Split(cd, right, rndRight.x, rndRight.y);
    return vec4(ab - b, b, cd - d, d);
}

// The counts of the levels (K = 4: c[0..3], K = 8: c[0..7]) of n facets, node k drawing with pair rnd[k]. Written
// with constant indices only: on a software rasterizer a local array indexed by a variable lives in memory, not in
// registers, and an earlier loop over the nodes cost the lighting pass about a third more (docs/area_lights.md).
// The second group runs only for K = 8 (the same branch for every pixel).
void kk25Multinomial(float n, Kk25Tree tree, vec2 rnd[7], out float c[8]) {
    float low = n, high = 0.0;
    if (tree.levels > 4) {
        high = kk25Split(n, tree.node[6], rnd[6].x, rnd[6].y);
        low = n - high;
    }
    vec4 lowCounts = kk25Group(low, tree.node[0], tree.node[1], tree.node[2], rnd[0], rnd[1], rnd[2]);
    vec4 highCounts = vec4(0.0);
    if (tree.levels > 4)
        highCounts = kk25Group(high, tree.node[3], tree.node[4], tree.node[5], rnd[3], rnd[4], rnd[5]);
    c = float[8](lowCounts.x, lowCounts.y, lowCounts.z, lowCounts.w, highCounts.x, highCounts.y, highCounts.z,
                 highCounts.w);
}
