// Deliot & Belcour 2023, "Real-time rendering of glinty appearances using distributed binomial laws on
// anisotropic grids" (Computer Graphics Forum 42(8)). Interface: shaders/glints/README.md.
//
// Sec. 3 (Eq. 2-4): the NDF D of Cook-Torrance is replaced by a counting process
//     D_P(h) = D(n)/R * b(N(P), R D(h)/D(n)) / N(P),
// for any target NDF D (GGX or Beckmann here), R = microfacet roughness ratio, N(P) facets in the footprint P.
// Sec. 4 (Eq. 9-10): facets are stratified on virtual grids; footprints between grid levels distribute the binomial
// law over the enclosing grids (a sum of binomials with area weights), never a lerp of binomial outputs.
// Sec. 5 (Eq. 11-14, Fig. 5-6): the grids are anisotropic: isotropic scale 2^lod, anisotropy ratio 2^k and an
// orientation whose discretization doubles with each ratio level; chosen from the UV footprint ellipse.
// Sec. 6.1: the (ratio, orientation, scale) cell is tetrahedralized: 4 grids per evaluation.
// Sec. 6.2: each grid is a simplex (triangle) grid: 3 vertices with barycentric weights (hexagonal glints).
// Eq. 14: bilinear interpolation over 4 cells of a hemispherical grid indexed by the orthographic projection of h.
// Sec. 6.3: gated Gaussian binomial with random numbers from a texture (glints/deliot2023_binomial.glsl).
// Where the paper is vague or the authors' supplemental code differs from its text, the default follows their code
// and the other reading is a parameter (docs/deliot2023.md): per-vertex normalization of the randomized counts
// (`normalization`), an angular cell R wide in projected-h units (`angular_grid`), the soft gate (`gate`).
// Total: 4 grids x 3 spatial vertices x 4 angular cells = 48 binomial evaluations per pixel and light.
// Per-pixel work (footprint, grids, vertex hashes, facet counts) is in glintSetup, shared by every light.
//
// Kneiphof & Klein 2024, "Real-Time Rendering of Glints in the Presence of Area Lights" (Pacific Graphics 2024,
// arXiv 2408.13611), `probability` = kk24 (default): Eq. 4's ad-hoc p = R D(h) / D(n) becomes the fraction of facets
// whose mirror direction hits the light, p = [integral over the light of D(h) / (4 |l.h|) dl] / [integral of D over
// the hemisphere of half vectors] (Sec. 4); the total NDF fitted as 1 + alpha^1.4109 (`total_ndf` = fit) or exact.
// Area lights (glintAreaFactor): the integral is the NDF-only pre-integrated term times the light's LTC integral
// (Sec. 4.2; the specular lobe's LTC by default, `light_integral` = ndf_ltc their dedicated one), the count is drawn
// on this grid with the light's centre direction picking the angular cell, and count / (N p) multiplies the LTC
// specular. Punctual and directional lights are lights of a solid angle Omega: p = D(h) Omega / (4 (l.h)) / total
// (Sec. 4.3; the sun's 0.53 degrees give 6.7e-5 sr).
// Deviation (`facets` = cone, the default): our facets reflect within a cone (the glint material's angular size,
// mapped to R: a cone of pi alpha^2 R steradians of half vectors, Eq. 4 at h = n), which the light's solid angle
// widens: p gains pi alpha^2 R D(h) / total. The paper's facets are mirrors (`facets` = mirror): a punctual light
// (Omega = 0) would then show no glint at all, and the glint material's angular size would change nothing.
#include "glints/deliot2023/deliot2023_binomial.glsl"
#include "glints/deliot2023/deliot2023_multinomial.glsl"

// Kneiphof & Klein 2024's parameters, at the table's defaults for user methods that include this file as a helper
// and declare only deliot2023's older parameters (content/methods/deliot2023_smoothstep.glsl).
#ifndef P_PROBABILITY
#define P_PROBABILITY 0.0
#endif
#ifndef P_TOTAL_NDF
#define P_TOTAL_NDF 0.0
#endif
#ifndef P_LIGHT_INTEGRAL
#define P_LIGHT_INTEGRAL 0.0
#endif
#ifndef P_FACETS
#define P_FACETS 0.0
#endif

const int DELIOT_VERTICES = 12;          // 4 grids (Sec. 6.1) x 3 simplex vertices (Sec. 6.2)
const int DELIOT_MAX_RATIO_LEVEL = 16;   // numeric guard only (ratio 65536): never reached by real footprints

struct GlintPixel {
    ivec2 texel[DELIOT_VERTICES];        // noise texel of each spatial vertex (hash of cell id and grid seed)
    float trials[DELIOT_VERTICES];       // w_i N_i: this grid's share of the footprint's facets (Eq. 10)
    float countWeight[DELIOT_VERTICES];  // weight of the vertex's count in D R / D(n) (Eq. 3, normalization)
    float invTotalFacets;                // 1 / sum(barycentric weight * trials): the footprint's facets
    bool softGate;                       // the authors' soft gate instead of Eq. 18's Heaviside
    float angularCellSize;               // cell of the hemispherical grid in projected-h units (Eq. 14)
    float Dn;                            // D(n), the NDF at the shading normal (Eq. 4)
    float totalNdf;                      // integral of D over the hemisphere (Kneiphof & Klein 2024, Sec. 4)
    float facetCone;                     // solid angle of half vectors one facet reflects (pi alpha^2 R; 0: mirrors)
    vec4 footprint;                      // anisotropy ratio, LOD, ratio level, orientation (radians)
};

// e^(x^2) erfc(x) for x >= 0 without overflow: the Chebyshev fit of erfc in Numerical Recipes (erfcc, fractional
// error < 1.2e-7) carries a factor e^(-x^2), which cancels.
float deliotScaledErfc(float x) {
    float t = 1.0 / (1.0 + 0.5 * x);
    return t * exp(-1.26551223 + t * (1.00002368 + t * (0.37409196 + t * (0.09678418 + t * (-0.18628806 +
               t * (0.27886807 + t * (-1.13520398 + t * (1.48851587 + t * (-0.82215223 + t * 0.17087277)))))))));
}

// Kneiphof & Klein 2024, Sec. 4: the integral of D over the hemisphere of half vectors (not projected), the
// probability's denominator. GGX: their fit 1 + alpha^1.4109, or exactly 1 + alpha^2 ln((1 + k) / alpha) / k with
// k = sqrt(1 - alpha^2). Beckmann (theirs is GGX only): exactly 1 + sqrt(pi) alpha e^(1/alpha^2) erfc(1/alpha) / 2
// in both readings (tools/ltc_fit/ltc_fitter.cpp totalNdf derives both; the tests check them by quadrature).
float deliotTotalNdf(float alpha, int ndf) {
    alpha = clamp(alpha, 1e-4, 1.0);
    if (ndf == NDF_BECKMANN) return 1.0 + 0.88622693 * alpha * deliotScaledErfc(1.0 / alpha);
    if (P_TOTAL_NDF < 0.5) return 1.0 + pow(alpha, 1.4109);
    float k = sqrt(max(1.0 - alpha * alpha, 0.0));
    return k > 1e-4 ? 1.0 + alpha * alpha * log((1.0 + k) / alpha) / k : 2.0;
}

// Debug counters for --aov extra: binomial evaluations and glintD calls of this pixel.
int g_deliotEvaluations = 0;
int g_deliotLightCalls = 0;

// One grid of Sec. 5: isotropic scale 2^lod, ratio 2^ratioLevel, orientation index at that ratio level.
struct DeliotGrid {
    int lod;
    int ratioLevel;
    int orientation;
    float weight;   // tetrahedral barycentric weight (Sec. 6.1)
};

// Orientation bins: 90 degrees / 2^k at ratio level k (45 deg at ratio 2, 22.5 at 4, ...): one orientation is added
// between each pair when the ratio doubles (Fig. 6). Orientations live on [0, pi) (an ellipse axis is a line).
// Level 0 (isotropic) ignores orientation, so its 90-degree bins only index the pentagon cells.
float deliotOrientationStep(int ratioLevel) { return (0.5 * PI) * exp2(-float(ratioLevel)); }

// Grid index -> transform of UV (Eq. 12: uv' = R_phi(S_1,r(S_s(uv)))) and the grid's random seed.
// Ratio level 0 is the isotropic grid: orientation must not change its random numbers (Sec. 5.2), so every
// orientation index maps to the same unrotated grid.
void deliotGridFrame(DeliotGrid grid, out float angle, out uint seed) {
    int orientations = int(round(PI / deliotOrientationStep(grid.ratioLevel)));
    int o = grid.ratioLevel == 0 ? 0 : ((grid.orientation % orientations) + orientations) % orientations;
    angle = float(o) * deliotOrientationStep(grid.ratioLevel);
    seed = deliotHash3(uvec3(uint(grid.lod + 4096), uint(grid.ratioLevel), uint(o))).x;
}

// Tetrahedral split of a prism (triangle x [0, 1] in scale) with vertex order v0 < v1 < v2: the upper level
// takes the weight t greedily in that order, which leaves at most 4 non-zero weights and, since every cell orders
// its vertices the same global way, matching faces between neighbouring cells (continuous weights).
void deliotPrismWeights(float b[3], float t, out float lower[3], out float upper[3]) {
    upper[0] = min(t, b[0]);
    upper[1] = clamp(t - upper[0], 0.0, b[1]);
    upper[2] = clamp(t - upper[0] - upper[1], 0.0, b[2]);
    for (int j = 0; j < 3; ++j) lower[j] = max(b[j] - upper[j], 0.0);
}

// erfinv in single precision (M. Giles, "Approximating the erfinv function", GPU Computing Gems, 2010): the
// density_normal=exact variate.
float deliotErfinv(float x) {
    float w = -log(max((1.0 - x) * (1.0 + x), 1e-30));
    float p;
    if (w < 5.0) {
        w -= 2.5;
        p = 2.81022636e-08;
        p = 3.43273939e-07 + p * w;
        p = -3.5233877e-06 + p * w;
        p = -4.39150654e-06 + p * w;
        p = 0.00021858087 + p * w;
        p = -0.00125372503 + p * w;
        p = -0.00417768164 + p * w;
        p = 0.246640727 + p * w;
        p = 1.50140941 + p * w;
    } else {
        w = sqrt(w) - 3.0;
        p = -0.000200214257;
        p = 0.000100950558 + p * w;
        p = 0.00134934322 + p * w;
        p = -0.00367342844 + p * w;
        p = 0.00573950773 + p * w;
        p = -0.0076224613 + p * w;
        p = 0.00943887047 + p * w;
        p = 1.00167406 + p * w;
        p = 2.83297682 + p * w;
    }
    return p * x;
}

GlintPixel glintSetup(GlintSurface s) {
    GlintPixel px;
    // --- Sec. 5.1: footprint ellipse (major/minor axes of the UV footprint from the G-buffer derivatives).
    FootprintEllipse e = footprintEllipse(s.duvdx, s.duvdy);
    float major = max(e.major, 1e-20);
    // Degenerate ellipses (collinear derivatives): bound the ratio instead of dividing by ~0.
    float minor = max(e.minor, major * exp2(-float(DELIOT_MAX_RATIO_LEVEL)));
    float ratio = major / minor;
    // LOD from the minor axis (the grid cell spans screen_space_scale pixels across the footprint).
    // floor() for both the level and its blend weight (ports that truncate break for negative LODs).
    float lod = clamp(log2(minor * P_SCREEN_SPACE_SCALE), -100.0, 100.0);
    float lod0 = floor(lod);
    // Eq. 10 weights are linear in area: w = (P - P_lo) / (P_hi - P_lo) with P = 4^lod.
    float scaleT = (exp2(2.0 * (lod - lod0)) - 1.0) / 3.0;
    // Ratio levels 2^k, area-linear blend to the next level (x2).
    int k0 = clamp(int(floor(log2(ratio))), 0, DELIOT_MAX_RATIO_LEVEL - 1);
    float ratio0 = exp2(float(k0));
    float ratioT = clamp((ratio - ratio0) / ratio0, 0.0, 1.0);
    float phi = atan(e.majorDir.y, e.majorDir.x);
    phi = phi < 0.0 ? phi + PI : phi;   // [0, pi): negative angles folded (a known port bug)
    float step0 = deliotOrientationStep(k0);
    float orientationPos = phi / step0;
    int o0 = int(floor(orientationPos));
    float orientT = clamp(orientationPos - float(o0), 0.0, 1.0);

    // --- Sec. 6.1: the (orientation, ratio) cell is a pentagon: lower level k0 with orientations A = o0, B = o0 + 1,
    // upper level k0 + 1 (half the step) with C = 2 o0, M = 2 o0 + 1, E = 2 o0 + 2. Split into 3 triangles
    // (A C M), (A B M), (B M E), vertices listed in the global order lower < upper, left < right.
    // Point: x = orientT, y = ratioT.
    float x = orientT, y = ratioT;
    ivec2 tri[3];     // (ratio level, orientation index at that level) of each triangle vertex
    float bary[3];
    ivec2 A = ivec2(k0, o0), B = ivec2(k0, o0 + 1);
    ivec2 C = ivec2(k0 + 1, 2 * o0), M = ivec2(k0 + 1, 2 * o0 + 1), E = ivec2(k0 + 1, 2 * o0 + 2);
    if (k0 == 0) {
        // Ratio level 0 is one isotropic grid whatever the orientation (A == B): the pentagon is a fan of two
        // triangles around it. Keeping A and B apart would draw two binomials from the same random numbers.
        if (x < 0.5) { tri[0] = A; tri[1] = C; tri[2] = M; bary[0] = 1.0 - y; bary[1] = y * (1.0 - 2.0 * x); bary[2] = y * 2.0 * x; }
        else         { tri[0] = A; tri[1] = M; tri[2] = E; bary[0] = 1.0 - y; bary[1] = y * (2.0 - 2.0 * x); bary[2] = y * (2.0 * x - 1.0); }
    } else if (x <= 0.5 * y) {
        tri[0] = A; tri[1] = C; tri[2] = M;
        bary[0] = 1.0 - y; bary[1] = y - 2.0 * x; bary[2] = 2.0 * x;
    } else if (x >= 1.0 - 0.5 * y) {
        tri[0] = B; tri[1] = M; tri[2] = E;
        bary[0] = 1.0 - y; bary[1] = 2.0 * (1.0 - x); bary[2] = y - 2.0 * (1.0 - x);
    } else {
        tri[0] = A; tri[1] = B; tri[2] = M;
        bary[1] = x - 0.5 * y; bary[2] = y; bary[0] = 1.0 - bary[1] - bary[2];
    }
    for (int j = 0; j < 3; ++j) bary[j] = max(bary[j], 0.0);
    float lower[3], upper[3];
    deliotPrismWeights(bary, scaleT, lower, upper);
    // The 4 tetrahedron vertices (Sec. 6.1): the 6 prism corners of which at most 4 carry weight. Which 4 follows
    // from the greedy split: t <= b0 -> {v0 v1 v2 lower, v0 upper}; t <= b0 + b1 -> {v1 v2 lower, v0 v1 upper};
    // else {v2 lower, v0 v1 v2 upper}.
    DeliotGrid grids[4];
    int tet = scaleT <= bary[0] ? 0 : (scaleT <= bary[0] + bary[1] ? 1 : 2);
    int lodLo = int(lod0), lodHi = int(lod0) + 1;
    #define DELIOT_GRID(v, level, w) DeliotGrid(level, tri[v].x, tri[v].y, w)
    if (tet == 0) {
        grids[0] = DELIOT_GRID(0, lodLo, lower[0]); grids[1] = DELIOT_GRID(1, lodLo, lower[1]);
        grids[2] = DELIOT_GRID(2, lodLo, lower[2]); grids[3] = DELIOT_GRID(0, lodHi, upper[0]);
    } else if (tet == 1) {
        grids[0] = DELIOT_GRID(1, lodLo, lower[1]); grids[1] = DELIOT_GRID(2, lodLo, lower[2]);
        grids[2] = DELIOT_GRID(0, lodHi, upper[0]); grids[3] = DELIOT_GRID(1, lodHi, upper[1]);
    } else {
        grids[0] = DELIOT_GRID(2, lodLo, lower[2]); grids[1] = DELIOT_GRID(0, lodHi, upper[0]);
        grids[2] = DELIOT_GRID(1, lodHi, upper[1]); grids[3] = DELIOT_GRID(2, lodHi, upper[2]);
    }
    #undef DELIOT_GRID

    // --- Sec. 6.2: simplex surface grid per virtual grid; Sec. 4.1 stratified facets: N = density x cell area.
    float baseLogDensity = P_LOG_DENSITY;
    float total = 0.0;
    float vertexFacets[DELIOT_VERTICES];
    float barycentric[DELIOT_VERTICES];
    for (int i = 0; i < 4; ++i) {
        float angle;
        uint seed;
        deliotGridFrame(grids[i], angle, seed);
        float c = cos(angle), sn = sin(angle);
        // Rotate UV by -angle (the grid's long axis along the footprint's major axis), stretch by the ratio along
        // it, scale by 2^-lod: one grid cell = 2^lod x (2^lod 2^k) in UV.
        vec2 r = vec2(c * s.uv.x + sn * s.uv.y, -sn * s.uv.x + c * s.uv.y);
        vec2 g = vec2(r.x * exp2(-float(grids[i].ratioLevel)), r.y) * exp2(-float(grids[i].lod));
        // Skew to the simplex lattice (equilateral triangles of unit edge: lattice basis (1, 0), (1/2, sqrt(3)/2)).
        // A skewed unit square is a rhombus; its short diagonal (1, 0)-(0, 1) splits it into two equilateral
        // triangles (splitting along (0, 0)-(1, 1) would give obtuse triangles and streaky glints).
        vec2 sk = vec2(g.x - 0.57735027 * g.y, 1.15470054 * g.y);
        vec2 base = floor(sk);
        vec2 f = sk - base;
        ivec2 cell0 = ivec2(base);
        ivec2 cells[3];
        float lambda[3];
        cells[1] = cell0 + ivec2(1, 0);
        cells[2] = cell0 + ivec2(0, 1);
        if (f.x + f.y < 1.0) { cells[0] = cell0;               lambda[0] = 1.0 - f.x - f.y; lambda[1] = f.x; lambda[2] = f.y; }
        else                 { cells[0] = cell0 + ivec2(1, 1); lambda[0] = f.x + f.y - 1.0; lambda[1] = 1.0 - f.y; lambda[2] = 1.0 - f.x; }
        // Facets per vertex of this grid: exp(log density) per unit UV area x cell area x material density scale.
        float cellArea = exp2(2.0 * float(grids[i].lod) + float(grids[i].ratioLevel));
        for (int v = 0; v < 3; ++v) {
            uvec3 hv = deliotHash3(uvec3(uint(cells[v].x), uint(cells[v].y), seed));
            int index = 3 * i + v;
            px.texel[index] = ivec2(int(hv.x & uint(DELIOT_NOISE_SIZE - 1)), int(hv.y & uint(DELIOT_NOISE_SIZE - 1)));
            // Density randomization: per-vertex log density ~ Normal(log density, sigma), clamped to [0, 50]. The
            // normal variate is an Irwin-Hall sum of 4 uniforms from the hash's unused bits (mean 0, variance 1,
            // tails cut at 3.46 sigma): Box-Muller's log and cos at 12 vertices tripled the cost of a pixel on llvmpipe.
            vec4 uniforms = vec4(uvec4(hv.x >> 16u, hv.y >> 16u, hv.z >> 16u, hv.z & 0xffffu)) * (1.0 / 65536.0);
            float gauss = (dot(uniforms, vec4(1.0)) - 2.0) * 1.7320508;
            // density_normal=exact: the authors' variate, sqrt(2) erfinv(2u - 1) of one uniform (unbounded tails
            // within float precision; issue 36's residual, docs/deliot2023.md).
            if (P_DENSITY_NORMAL > 0.5) {
                float u = (float(((hv.x >> 16u) << 8u) | (hv.z >> 24u)) + 0.5) * (1.0 / 16777216.0);
                gauss = 1.41421356 * deliotErfinv(2.0 * u - 1.0);
            }
            float logDensity = clamp(baseLogDensity + P_DENSITY_RANDOMIZATION * gauss, 0.0, 50.0);
            float facets = exp(logDensity) * cellArea * max(s.densityScale, 0.0);
            px.trials[index] = grids[i].weight * facets;
            vertexFacets[index] = facets;
            barycentric[index] = max(lambda[v], 0.0);
            total += barycentric[index] * px.trials[index];
        }
    }
    px.invTotalFacets = total > 0.0 ? 1.0 / total : 0.0;
    // Eq. 3's "/ N". vertex (authors' supplemental, where the density randomization comes from): each vertex's
    // count over its own randomized facets, weighted by barycentric x tetrahedral weight, which keeps E[D_P] = D
    // (the weights sum to 1) and keeps each vertex's clumping. footprint: the summed count over the footprint's
    // total, also mean-preserving, which averages the randomization away (a much lower CV: docs/deliot2023.md).
    bool perVertex = P_NORMALIZATION < 0.5;
    for (int v = 0; v < DELIOT_VERTICES; ++v)
        px.countWeight[v] = perVertex ? (vertexFacets[v] > 0.0 ? barycentric[v] / vertexFacets[v] : 0.0)
                                      : barycentric[v] * px.invTotalFacets;
    px.softGate = P_GATE < 0.5;
    px.Dn = D_smooth(vec3(0.0, 0.0, 1.0), s.alpha, s.ndf);
    px.totalNdf = deliotTotalNdf(s.alpha, s.ndf);
    px.facetCone = P_FACETS < 0.5 ? PI * s.alpha * s.alpha * P_MICROFACET_ROUGHNESS : 0.0;
    // Eq. 14 hemispherical grid, subdivided for micro-roughness. projected (authors' code): a cell is R wide in
    // units of the orthographic projection of h, which sets how long a glint lives as the light or view moves
    // (their grid indexes |h.x|, |h.y|, mirroring the pattern about the tangent axes: not reproduced). lobe (an
    // earlier reading): a cell holds the fraction R of the lobe's projected area 1 / D(n), sqrt(R / D(n)) wide.
    px.angularCellSize = P_ANGULAR_GRID < 0.5 ? P_MICROFACET_ROUGHNESS : sqrt(P_MICROFACET_ROUGHNESS / max(px.Dn, 1e-20));
    px.footprint = vec4(ratio, lod, float(k0) + ratioT, phi);
    return px;
}

// Eq. 10 + 18: the footprint's count of facets that reflect with probability p, over its facets (the / N is in
// countWeight): expectation p. The angular cell of Eq. 14 comes from h.
float deliotCount(GlintPixel px, vec3 h, float p) {
    // Eq. 14: bilinear weights of the 4 hemispherical-grid cells around the projected half vector.
    vec2 q = h.xy / px.angularCellSize - 0.5;
    vec2 qBase = floor(q);
    vec2 f = q - qBase;
    ivec2 a0 = ivec2(qBase);
    // In textureGather order: cells a0 + (0, 1), a0 + (1, 1), a0 + (1, 0), a0.
    vec4 angularWeight = vec4((1.0 - f.x) * f.y, f.x * f.y, f.x * (1.0 - f.y), (1.0 - f.x) * (1.0 - f.y));
    float logMiss = deliotLogMiss(p);   // Eq. 16's log(1 - p): once per light
    float count = 0.0;
    int v = 0;
    do {   // tested at the bottom (lights/ltc.glsl ltcLoopCount: a top-tested loop cost llvmpipe one more pass)
        // Eq. 10 + 18: this grid vertex's share w_i N_i of the footprint's facets, drawn from the gated binomial
        // with the random numbers of each of the 4 angular cells (the law's parameters are shared by the 4 draws).
        DeliotBinomialLaw law = deliotBinomialLaw(px.trials[v], p, logMiss, px.softGate);
        uvec4 packedPairs = deliotNoiseGather(px.texel[v], a0);
        float vertexCount = 0.0;
        for (int a = 0; a < 4; ++a) {
            vec2 rnd = deliotUnpackNoise(packedPairs[a]);
            vertexCount += angularWeight[a] * deliotDrawBinomial(law, rnd.x, rnd.y);
        }
        g_deliotEvaluations += 4;
        count += px.countWeight[v] * vertexCount;
    } while (++v < glintLoopCount(DELIOT_VERTICES));
    return count;
}

// The probability that one facet reflects the current light (g_glintLight) towards the eye through h.
// db23: Eq. 4, p = R D(h) / D(n), in [0, R] for NDFs peaking at the normal (area lights: at their centre direction).
// kk24: Kneiphof & Klein 2024, Sec. 4, [integral over the light of D(h) / (4 |l.h|) + facet cone x D(h)] / total.
float deliotProbability(GlintPixel px, GlintSurface s, vec3 h, float lightIntegral) {
    float D = D_smooth(h, s.alpha, s.ndf);
    if (P_PROBABILITY > 0.5) return clamp(P_MICROFACET_ROUGHNESS * D / max(px.Dn, 1e-30), 0.0, 1.0);
    return clamp((lightIntegral + px.facetCone * D) / px.totalNdf, 0.0, 1.0);
}

float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    g_deliotLightCalls += 1;
    float p = deliotProbability(px, s, h, g_glintLight.ndfIntegral);
    if (!(p > 0.0)) return 0.0;
    // Eq. 3-4: D_P = D(h) / p x count / N (= D(n) / R x count / N with Eq. 4's p); expectation D(h).
    // max_ratio: the authors' clamp of D_P at 20 D(n) (0 = none, the default).
    float dp = D_smooth(h, s.alpha, s.ndf) / p * deliotCount(px, h, p);
    return P_MAX_RATIO > 0.0 ? min(dp, P_MAX_RATIO * px.Dn) : dp;
}

#ifdef GLIMMER_LIGHTING_PASS
// Area lights (lighting.frag; shaders/glints/README.md "Extended lights"), Kneiphof & Klein 2024, Sec. 4-5: the
// count under the light's probability over its expectation, multiplying the LTC specular.
#define GLINT_AREA_LIGHTS 1
vec3 glintAreaFactor(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    g_deliotLightCalls += 1;
    // Sec. 4.2: the NDF-only term times an LTC integral over the light; the specular lobe's LTC (the lighting pass
    // computed it) or the dedicated NDF-only LTC fitted by tools/ltc_fit.
    float integral = g_glintLight.ndfIntegral;
    if (P_LIGHT_INTEGRAL > 0.5)
        integral = g_glintLight.ndfOnlyMagnitude * ltcAreaIntegral(g_glintLight.shape, g_glintLight.centre,
                                                                   g_glintLight.halfU, g_glintLight.halfV,
                                                                   g_glintLight.invNdfOnly);
    float p = deliotProbability(px, s, h, integral);
    if (!(p > 0.0)) return vec3(0.0);
    // max_ratio as in glintD: the factor times D(h) is D_P, clamped at max_ratio D(n).
    float factor = deliotCount(px, h, p) / p;
    float D = D_smooth(h, s.alpha, s.ndf);
    return vec3(P_MAX_RATIO > 0.0 && D > 0.0 ? min(factor, P_MAX_RATIO * px.Dn / D) : factor);
}
#endif

// Environment glints (shaders/glints/README.md "Environment glints"), Kneiphof & Klein 2025, Sec. 4.2: a facet
// reflects the visible hemisphere with p_base = (NDF-only integral) / total NDF, and level i of the environment with
// p_i = p_base w_i (level 0, radiance 0, also takes the 1 - p_base that reflect nothing); each grid vertex's facets
// are shared among the levels by the hierarchical multinomial (glints/deliot2023/deliot2023_multinomial.glsl) on this method's
// grid (no angular cell: the environment has no single half vector), and the glint attenuation
// sum_i L_i D_i / sum_i L_i p_i (expectation 1) multiplies the split-sum specular.
#define GLINT_ENVIRONMENT 1
float glintEnvironmentFactor(GlintPixel px, GlintSurface s, GlintEnvironment env) {
    if (env.levels <= 1) return 1.0;
    float pBase = clamp(env.ndfIntegral / px.totalNdf, 0.0, 1.0);
    float p[8];
    float expected = 0.0;
    for (int i = 0; i < 8; ++i) {
        p[i] = pBase * env.weight[i];
        expected += env.radiance[i] * p[i];
    }
    p[0] += 1.0 - pBase;
    if (!(expected > 0.0)) return 1.0;
    Kk25Tree tree = kk25Tree(p, env.levels);   // the splits' probabilities and logs: once per pixel
    float D[8] = float[8](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    int v = 0;
    do {   // tested at the bottom, as deliotCount's; `continue` goes to the test
        if (!(px.countWeight[v] > 0.0)) continue;   // a grid vertex of weight 0 (the tetrahedral split's)
        // 7 noise pairs per vertex, from two 2 x 2 blocks of its noise texels away from its angular cells (the
        // angular grid spans |h.xy| / R <= 1 / R cells around the vertex's texel).
        uvec4 first = deliotNoiseGather(px.texel[v], ivec2(-613, 401));
        uvec4 second = env.levels > 4 ? deliotNoiseGather(px.texel[v], ivec2(419, -887)) : first;
        vec2 rnd[7];
        for (int k = 0; k < 4; ++k) rnd[k] = deliotUnpackNoise(first[k]);
        for (int k = 0; k < 3; ++k) rnd[4 + k] = deliotUnpackNoise(second[k]);
        if (env.levels <= 4) rnd[6] = rnd[3];
        float c[8];
        kk25Multinomial(px.trials[v], tree, rnd, c);
        for (int i = 0; i < 8; ++i) D[i] += px.countWeight[v] * c[i];
    } while (++v < glintLoopCount(DELIOT_VERTICES));
    float observed = 0.0;
    for (int i = 0; i < 8; ++i) observed += env.radiance[i] * D[i];
    return observed / expected;
}

vec4 glintFootprintAOV(GlintPixel px, GlintSurface s) { return px.footprint; }

// x: binomial evaluations per glintD call (48 = 4 grids x 3 vertices x 4 angular cells), y: total evaluations,
// z: glintD calls (lights evaluated), w: 1 / sum of distributed facets (0 when none).
vec4 glintExtraAOV(GlintPixel px, GlintSurface s) {
    float perCall = g_deliotLightCalls > 0 ? float(g_deliotEvaluations) / float(g_deliotLightCalls) : 0.0;
    return vec4(perCall, float(g_deliotEvaluations), float(g_deliotLightCalls), px.invTotalFacets);
}
