// Kemppinen et al. 2025, Sec. 3.3.5 and Algorithm 2: importance sampling of the filtered glinty NDF D*^f,
// returning the half vector and its solid-angle pdf. Include after glints/kemppinen2025.glsl (it uses
// GlintPixel and the core). CPU twin: sampleHalfVector / samplePriorPdf in engine/reference/kemppinen2025_reference.
//
// One sample: a point process by triplanar weight; a level by lambda's roulette (lines 4-6); with probability
// rho_l a defensive sample of the smooth NDF with density D(h) h.z (the compensation term, which the paper leaves
// unsampled, would otherwise have no pdf where no explicit lobe reaches; D cos rather than uniform in U because for
// GGX the uniform prior is not D cos, and D cos cancels the D(h) factor of every term of Eq. 11); otherwise x_a uniform over the
// prior square (line 2; the square rather than the disk makes the block probabilities exact rectangles), the
// reservoir over the terms of B(x_a) (lines 9-15, weights R N_s m_t(B) Luminance(c)) and a truncated Gaussian
// inside B for the chosen term (line 14). Each term's lobe is the Gaussian centred on its point with
// sigma = alpha* sqrt(D(T^-1(g_a))) (the evaluation uses sigma at the query direction: the sampler is close to,
// not exactly proportional to, D*^f; the pdf is exact for what is sampled). The pdf sums over every block that
// contains the sample (deviation from the pdf line of Algorithm 2, which ignores that x_a is random).

// PCG-RXS-M-XS 32 (O'Neill): uniform floats in [0, 1) with 24 bits.
float kemppinenRandom(inout uint state) {
    state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    word = (word >> 22u) ^ word;
    return float(word >> 8u) * (1.0 / 16777216.0);
}

uint kemppinenSeed(uint seed) { return seed * 747796405u + 2891336453u; }

float kemppinenDefensiveProbability(GlintPixel px, int ndf, int level) {
    float sigma = px.microRoughness * sqrt(kemppinenSmoothD(vec3(0.0, 0.0, 1.0), px.alpha, ndf));
    float inside = kemppinenErf(float(px.neighbourSide) * exp2(-float(level)) / (2.0 * sqrt(2.0) * sigma));
    return max(0.1, 1.0 - inside * inside);
}

// |J_T|: prior area per solid angle (GGX: 1 / (8 ax ay |M^T h|^3); Beckmann: pi D cos / 4).
float kemppinenPriorJacobian(vec3 h, vec2 alpha, int ndf) {
    if (h.z <= 0.0) return 0.0;
    if (ndf == NDF_BECKMANN) return PI * kemppinenBeckmannD(h, alpha) * h.z / 4.0;
    float v = length(vec3(h.xy / alpha, h.z));
    return 1.0 / (8.0 * alpha.x * alpha.y * v * v * v);
}

// Half vector with density D(h) h.z: D cos dw = P22(slope) d(slope), and the slope distributions of GGX and
// Beckmann are stretch-invariant, so the unit-roughness slope radius (Walter et al. 2007, Eq. 28 / 35 with
// alpha = 1) is stretched by alpha.
vec3 kemppinenSampleSmoothNdfCos(vec2 alpha, int ndf, float u1, float u2) {
    float tan2 = ndf == NDF_BECKMANN ? -log(max(1.0 - u1, 1e-12)) : u1 / max(1.0 - u1, 1e-12);
    float phi = 2.0 * PI * u2, r = sqrt(tan2);
    return normalize(vec3(r * cos(phi) * alpha.x, r * sin(phi) * alpha.y, 1.0));
}

// That density in prior space, D(h) h.z / |J_T(h)| at h = T^-1(xa): 4 / pi for Beckmann (T carries D cos to the
// uniform disk), 8 h.z / (pi |M^T h|) for GGX.
float kemppinenDefensivePriorPdf(vec2 xa, vec2 alpha, int ndf) {
    if (ndf == NDF_BECKMANN) return 4.0 / PI;
    vec3 h = kemppinenFromPrior(xa, alpha, ndf);
    float v = length(vec3(h.xy / alpha, h.z));
    return 8.0 * h.z / (PI * v);
}

// One explicit term of a block in the stretched angular space x_a'.
struct KemppinenTerm {
    vec2 centre;
    float sigma;
    float weight;   // R N_s Luminance(c); 0 when the point is absent
};

KemppinenTerm kemppinenBlockTerm(GlintPixel px, int ndf, KemppinenProcess proc, int q, int level, float levelWeight,
                                 ivec2 cellA, int spatialIndex) {
    KemppinenTerm t;
    t.weight = 0.0;
    t.centre = vec2(0.0);
    t.sigma = 1.0;
    vec2 extent = 1.0 / px.angularStretch;
    float resA = exp2(float(level));
    ivec2 cellsA = ivec2(ceil(extent * resA));
    if (any(lessThan(cellA, ivec2(0))) || any(greaterThanEqual(cellA, cellsA))) return t;
    int li = level - proc.level;
    ivec2 offset = ivec2(spatialIndex & 1, spatialIndex >> 1);
    KemppinenPoint p = kemppinenPoint(proc.baseCell[li] + offset, cellA, level, q);
    t.centre = (vec2(cellA) + p.angular) / resA;
    vec2 ga = t.centre / extent;
    if (dot(ga - 0.5, ga - 0.5) >= 0.25) return t;
    vec2 ds = proc.local[li] - vec2(offset) - p.spatial;
    vec3 invCovS = proc.invCovCell[li];
    // Below e^-50 the term is absent (the CPU twin cuts at the same exponent: float underflows where double does
    // not, and the reservoir draws one random number per present term).
    float exponent = max(ds.x * ds.x * invCovS.x + 2.0 * ds.x * ds.y * invCovS.y + ds.y * ds.y * invCovS.z, 0.0);
    float spatial = exponent < 100.0 ? exp(-0.5 * exponent) : 0.0;
    vec3 c = kemppinenGlintColor(p.hue, px.colorVariation);
    t.weight = kemppinenRoulette(p.roulette, levelWeight) * spatial * dot(c, vec3(0.2126, 0.7152, 0.0722));
    float d = kemppinenSmoothD(kemppinenFromPrior(ga, px.alpha, ndf), px.alpha, ndf);
    t.sigma = px.microRoughness * sqrt(d);
    if (d < 1e-20) t.weight = 0.0;   // as in the evaluation: no lobe where D underflows
    return t;
}

float kemppinenTermMass(KemppinenTerm t, vec2 lo, vec2 hi) {
    return kemppinenIntervalMass(t.centre.x, t.sigma, lo.x, hi.x) * kemppinenIntervalMass(t.centre.y, t.sigma, lo.y, hi.y);
}

// Truncated normal on [lo, hi] by inverting the CDF (an interval entirely above the mean is mirrored below it,
// where erf differences keep more precision).
float kemppinenSampleTruncatedNormal(float mean, float sigma, float lo, float hi, float u) {
    float a = (lo - mean) / (sqrt(2.0) * sigma), b = (hi - mean) / (sqrt(2.0) * sigma);
    bool mirrored = a > 0.0;
    if (mirrored) {
        float t = a;
        a = -b;
        b = -t;
    }
    float ea = kemppinenErf(a), eb = kemppinenErf(b);
    float target = ea + u * (eb - ea);
    // erf^-1 by bisection (Newton from a tail start diverges where erf is flat); erf is 1 beyond |x| = 6.
    float left = max(a, -6.0), right = min(b, 6.0);
    if (left > right) return mean + sqrt(2.0) * sigma * (mirrored ? -0.5 * (a + b) : 0.5 * (a + b));
    for (int i = 0; i < 32; ++i) {
        float mid = 0.5 * (left + right);
        if (kemppinenErf(mid) < target) left = mid; else right = mid;
    }
    float x = 0.5 * (left + right);
    if (mirrored) x = -x;
    return mean + sqrt(2.0) * sigma * x;
}

// Sampler density in prior space at x_a.
float kemppinenSamplePriorPdf(GlintPixel px, int ndf, vec2 xa) {
    vec2 fromCentre = xa - 0.5;
    if (!px.hasGlints || dot(fromCentre, fromCentre) >= 0.25) return 0.0;
    int side = px.neighbourSide;
    vec2 extent = 1.0 / px.angularStretch;
    vec2 xPrime = xa * extent;
    float pdf = 0.0;
    for (int q = 0; q < px.processCount; ++q) {
        KemppinenProcess proc = px.process[q];
        for (int li = 0; li < 2; ++li) {
            int level = proc.level + li;
            float pLevel = li == 0 ? 1.0 - proc.levelFrac : proc.levelFrac;
            if (pLevel <= 0.0) continue;
            float levelWeight = pLevel * proc.weight;
            float rho = kemppinenDefensiveProbability(px, ndf, level);
            float p = rho * kemppinenDefensivePriorPdf(xa, px.alpha, ndf);
            float resA = exp2(float(level));
            ivec2 cell = ivec2(floor(xPrime * resA));
            float offset = 0.5 * float(side) - 0.5;
            for (int b = 0; b < side * side; ++b) {
                ivec2 a0 = cell - ivec2(b % side, b / side);
                vec2 selLo = max((vec2(a0) + offset) / resA, vec2(0.0));
                vec2 selHi = min((vec2(a0) + offset + 1.0) / resA, extent);
                if (selHi.x <= selLo.x || selHi.y <= selLo.y) continue;
                float pBlock = (selHi.x - selLo.x) * (selHi.y - selLo.y);
                vec2 lo = max(vec2(a0) / resA, vec2(0.0));
                vec2 hi = min(vec2(a0 + side) / resA, extent);
                float total = 0.0, density = 0.0;
                for (int c = 0; c < side * side; ++c)
                    for (int si = 0; si < 4; ++si) {
                        KemppinenTerm t = kemppinenBlockTerm(px, ndf, proc, q, level, levelWeight,
                                                             a0 + ivec2(c % side, c / side), si);
                        if (t.weight <= 0.0) continue;
                        total += t.weight * kemppinenTermMass(t, lo, hi);
                        vec2 d = xPrime - t.centre;
                        float s2 = t.sigma * t.sigma;
                        density += t.weight * exp(-0.5 * dot(d, d) / s2) / (2.0 * PI * s2);
                    }
                float pInBlock = total > 0.0 ? density / total : 1.0 / ((hi.x - lo.x) * (hi.y - lo.y));
                p += (1.0 - rho) * pBlock * pInBlock;
            }
            pdf += proc.weight * pLevel * p;
        }
    }
    return pdf;
}

// Samples a shading-frame half vector from D*^f at the pixel; pdf over solid angle (0: no sample).
vec3 kemppinenSampleHalfVector(GlintPixel px, int ndf, inout uint rng, out float pdf, out vec2 prior) {
    pdf = 0.0;
    prior = vec2(0.5);
    if (!px.hasGlints) return vec3(0.0, 0.0, 1.0);
    int q = 0;
    float u = kemppinenRandom(rng), acc = 0.0;
    for (int i = 0; i < px.processCount; ++i) {
        acc += px.process[i].weight;
        q = i;
        if (u < acc) break;
    }
    KemppinenProcess proc = px.process[q];
    int level = kemppinenRandom(rng) < proc.levelFrac ? proc.level + 1 : proc.level;   // lines 4-6
    float levelWeight = (level == proc.level ? 1.0 - proc.levelFrac : proc.levelFrac) * proc.weight;
    vec2 extent = 1.0 / px.angularStretch;
    vec2 xPrime;
    if (kemppinenRandom(rng) < kemppinenDefensiveProbability(px, ndf, level)) {
        float u1 = kemppinenRandom(rng), u2 = kemppinenRandom(rng);
        xPrime = kemppinenToPrior(kemppinenSampleSmoothNdfCos(px.alpha, ndf, u1, u2), px.alpha, ndf) * extent;
    } else {
        int side = px.neighbourSide;
        float resA = exp2(float(level));
        vec2 xa = vec2(kemppinenRandom(rng), kemppinenRandom(rng)) * extent;                 // line 2
        ivec2 a0 = ivec2(floor(xa * resA - (0.5 * float(side) - 0.5)));
        vec2 lo = max(vec2(a0) / resA, vec2(0.0));
        vec2 hi = min(vec2(a0 + side) / resA, extent);
        float total = 0.0;
        KemppinenTerm chosen;
        chosen.weight = 0.0;
        for (int c = 0; c < side * side; ++c)                                                 // lines 9-10
            for (int si = 0; si < 4; ++si) {
                KemppinenTerm t = kemppinenBlockTerm(px, ndf, proc, q, level, levelWeight,
                                                     a0 + ivec2(c % side, c / side), si);
                if (t.weight <= 0.0) continue;
                float w = t.weight * kemppinenTermMass(t, lo, hi);                            // line 12
                total += w;                                                                   // line 13
                float r = kemppinenRandom(rng);
                if (w > 0.0 && r < w / total) chosen = t;                                     // line 15
            }
        if (chosen.weight <= 0.0) {
            xPrime = lo + vec2(kemppinenRandom(rng), kemppinenRandom(rng)) * (hi - lo);
        } else {                                                                              // line 14
            float ux = kemppinenRandom(rng), uy = kemppinenRandom(rng);
            xPrime = vec2(kemppinenSampleTruncatedNormal(chosen.centre.x, chosen.sigma, lo.x, hi.x, ux),
                          kemppinenSampleTruncatedNormal(chosen.centre.y, chosen.sigma, lo.y, hi.y, uy));
        }
    }
    prior = xPrime / extent;
    vec2 fromCentre = prior - 0.5;
    if (dot(fromCentre, fromCentre) >= 0.25) return vec3(0.0, 0.0, 1.0);                     // outside U
    vec3 h = kemppinenFromPrior(prior, px.alpha, ndf);                                       // line 16
    pdf = kemppinenSamplePriorPdf(px, ndf, prior) * kemppinenPriorJacobian(h, px.alpha, ndf);
    return h;
}
