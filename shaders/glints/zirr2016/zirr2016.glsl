// Baseline: Zirr & Kaplanyan 2016, "Real-time rendering of procedural multiscale materials" (I3D 2016), as the
// authors' own public shader runs it (facts measured against it, ../shared/methods.md; none of its code is used).
// Interface: shaders/glints/README.md. CPU twin: engine/glints/zirr2016_reference.cpp (keep both in step).
//  - Footprint: the axis-aligned box of the pixel's +-0.5 px parallelogram in UV (duv/dx, duv/dy).
//  - Random seeds live on axis-aligned mip grids on the surface. The level puts the box's short side between
//    1 and 2 cells (cells of 0.5-1 px); the long side is covered by up to 16 steps (beyond that the cells grow
//    isotropically: the stretched glints of Deliot & Belcour Fig. 11), each step a 2x2 bilinear lookup of cells.
//  - Each cell holds N = density x cell area facets; a facet reflects when its normal lies in the search cone of
//    half-angle gamma around h: p = D(h) (h.n) pi gamma^2 (the fraction of normals in that solid angle). One
//    angular cone per cell: the cone's seed is the cell of a hemispherical grid 2 gamma wide in projected h.
//  - The count is b(N, p) drawn by inverse CDF from one uniform: the pmf recursion up to 16 steps while N p <= 5,
//    else the Gaussian rounded, floor(N p + sigma Phi^-1(u) + 0.5) (A&S 26.2.23 for Phi^-1; rounding, not floor,
//    keeps the mean: a floor would lose half a count, 10 % at N p = 5).
//  - Levels of detail blend by lerping the two levels' normalized counts (their blend: the ghosting of D&B
//    Fig. 2, 10, and the variance loss of D&B Fig. 4).
//  - D_P = D(h) x (normalized count) / p, at most dynamic_range x D(h) (their dynamic-range clamp, 50000).
// Not reproduced: their float hash keys (float(cx + 1549 cy) collapse at metre-scale UVs; an integer hash here) and
// their per-cell random scaling of the facet count (`variation`, default 100), which raises the mean above the
// smooth NDF; without it every parameter kept here preserves the mean (docs/zirr2016.md).
// Extended lights (README "Extended lights"): the paper and the authors' shader know point lights only; an area
// light's glints are this NDF at its centre direction over the smooth NDF there (the lighting pass's fallback), the
// sun's and a point light's size (GlintLight) are not read: its search cone alone sets a glint's angular extent.

const int ZIRR_MAX_STEPS = 16;
const int ZIRR_MAX_PMF_STEPS = 16;

struct GlintPixel {
    vec2 firstStep;        // UV of the first step along the long side of the box
    vec2 stepUv;           // UV between steps
    int steps;             // 1..16
    int lod0;              // finer level; the coarser is lod0 + 1
    float lodT;            // lerp weight of the coarser level (fract of the continuous LOD)
    float facetsLo;        // facets per cell at lod0 (density x 4^lod0 x density scale)
    vec4 footprint;        // box ratio, LOD, steps, capped (1 when ratio > 16)
};

int g_zirrEvaluations = 0;
int g_zirrLightCalls = 0;

uvec3 zirrHash3(uvec3 v) {
    v = v * 747796405u + 2891336453u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v ^= v >> 16u;
    v.x += v.y * v.z;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    return v;
}

float zirrUnit(uint bits) { return (float(bits >> 8u) + 0.5) * (1.0 / 16777216.0); }

// Phi^-1(u), Abramowitz & Stegun 26.2.23 (|error| < 4.5e-4).
float zirrInverseNormal(float u) {
    float q = min(u, 1.0 - u);
    float t = sqrt(-2.0 * log(q));
    float x = t - (2.515517 + t * (0.802853 + t * 0.010328)) / (1.0 + t * (1.432788 + t * (0.189269 + t * 0.001308)));
    return u < 0.5 ? -x : x;
}

// b(N, p) by inverse CDF of one uniform u. N may be fractional (an expected facet count): N < 1 is one trial of
// probability N p.
float zirrBinomial(float N, float p, float u) {
    if (!(N > 0.0) || !(p > 0.0)) return 0.0;
    p = min(p, 1.0);
    if (N < 1.0) return u < N * p ? 1.0 : 0.0;
    if (p >= 1.0) return floor(N);
    float mean = N * p;
    if (mean > 5.0)
        return clamp(floor(mean + sqrt(mean * (1.0 - p)) * zirrInverseNormal(u) + 0.5), 0.0, floor(N));
    // P(0) = (1 - p)^N, with a series for log(1 - p) where float loses it; then pmf(k+1) = pmf(k) (N-k)/(k+1) p/(1-p).
    float logMiss = p < 0.05 ? -p * (1.0 + p * (0.5 + p * (1.0 / 3.0 + p * 0.25))) : log(1.0 - p);
    float pmf = exp(N * logMiss);
    float cdf = pmf;
    float odds = p / max(1.0 - p, 1e-30);
    float k = 0.0;
    for (int i = 0; i < ZIRR_MAX_PMF_STEPS && u >= cdf && k < N; ++i) {
        pmf *= (N - k) / (k + 1.0) * odds;
        k += 1.0;
        cdf += pmf;
    }
    return min(k, floor(N));
}

GlintPixel glintSetup(GlintSurface s) {
    GlintPixel px;
    // Axis-aligned box of the +-0.5 px parallelogram: full extents along u and v.
    vec2 extent = abs(s.duvdx) + abs(s.duvdy);
    float longSide = max(max(extent.x, extent.y), 1e-20);
    float shortSide = max(min(extent.x, extent.y), longSide * 1e-6);
    float ratio = longSide / shortSide;
    px.steps = clamp(int(ceil(ratio)), 1, ZIRR_MAX_STEPS);
    float covered = max(shortSide, longSide / float(ZIRR_MAX_STEPS));
    float lod = clamp(log2(covered), -100.0, 100.0);   // cell 2^floor(lod): 0.5-1 x the covered short side
    px.lod0 = int(floor(lod));
    px.lodT = lod - floor(lod);
    float density = exp(clamp(P_LOG_DENSITY, 0.0, 50.0)) * max(s.densityScale, 0.0);
    px.facetsLo = density * exp2(2.0 * float(px.lod0));
    vec2 dir = extent.x >= extent.y ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
    px.stepUv = dir * (longSide / float(px.steps));
    px.firstStep = s.uv - dir * (0.5 * longSide) + 0.5 * px.stepUv;
    px.footprint = vec4(ratio, lod, float(px.steps), ratio > float(ZIRR_MAX_STEPS) ? 1.0 : 0.0);
    return px;
}

float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    g_zirrLightCalls += 1;
    if (h.z <= 0.0 || !(px.facetsLo > 0.0)) return 0.0;
    float D = D_smooth(h, s.alpha, s.ndf);
    float gamma = P_SEARCH_CONE;
    float p = clamp(D * h.z * PI * gamma * gamma, 0.0, 1.0);
    if (!(p > 0.0)) return 0.0;
    ivec2 cone = ivec2(floor(h.xy / (2.0 * gamma)));   // one angular cone per cell
    float level[2] = float[2](0.0, 0.0);
    for (int l = 0; l < 2; ++l) {
        int lod = px.lod0 + l;
        float facets = px.facetsLo * (l == 0 ? 1.0 : 4.0);
        float invSize = exp2(-float(lod));
        uint levelSeed = zirrHash3(uvec3(uint(lod + 4096), uint(cone.x), uint(cone.y))).x;
        for (int j = 0; j < px.steps; ++j) {
            // 2x2 bilinear coverage around the step's point (cell centres at integer + 0.5).
            vec2 q = (px.firstStep + float(j) * px.stepUv) * invSize - 0.5;
            vec2 base = floor(q);
            vec2 f = q - base;
            ivec2 c0 = ivec2(base);
            for (int a = 0; a < 4; ++a) {
                ivec2 o = ivec2(a & 1, a >> 1);
                float w = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
                ivec2 cell = c0 + o;
                float u = zirrUnit(zirrHash3(uvec3(uint(cell.x), uint(cell.y), levelSeed)).x);
                level[l] += w * zirrBinomial(facets, p, u);
            }
            g_zirrEvaluations += 4;
        }
        level[l] /= facets * float(px.steps);
    }
    // ZK16's lerp of the levels' normalized counts; E[count / N] = p, so D x (count / N) / p has mean D.
    float ratioToMean = mix(level[0], level[1], px.lodT) / p;
    return D * min(ratioToMean, P_DYNAMIC_RANGE);
}

vec4 glintFootprintAOV(GlintPixel px, GlintSurface s) { return px.footprint; }

// x: binomial draws per glintD call (2 levels x steps x 4 cells: varies with the footprint), y: total,
// z: glintD calls, w: 1 / facets of the footprint (steps x lerped cell facets).
vec4 glintExtraAOV(GlintPixel px, GlintSurface s) {
    float perCall = g_zirrLightCalls > 0 ? float(g_zirrEvaluations) / float(g_zirrLightCalls) : 0.0;
    float footprintFacets = px.facetsLo * mix(1.0, 4.0, px.lodT) * float(px.steps);
    return vec4(perCall, float(g_zirrEvaluations), float(g_zirrLightCalls),
                footprintFacets > 0.0 ? 1.0 / footprintFacets : 0.0);
}
