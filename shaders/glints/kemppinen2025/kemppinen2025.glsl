// Kemppinen et al. 2025, "Evaluating and Sampling Glinty NDFs in Constant Time" (ACM TOG 44(6), Art. 255):
// evaluation of the filtered semi-discrete NDF D*^f, Algorithm 1. CPU twin: engine/reference/kemppinen2025_reference.
// Extended lights (README "Extended lights"): the paper evaluates D* for point lights and importance-samples it for
// environments; an area light's glints are D* at its centre direction over the smooth NDF there (the lighting pass's
// fallback); the light's solid angle (GlintLight) is not convolved into the Gaussian glints (their angular width is
// alpha*: a light wider than that would widen them, which this reading leaves out).
//
// D*^f(x, h) = D(h) [ (1/N) sum_{i in B(k)} R_i c_i g_a(T(h) - mu_i; Sigma_a) g_s(x_i - x; Sigma_s) + C(h) E[c] ]
// (Eq. 5 and 11), with g normalised 2D Gaussians (the paper's N(.) is written with a 1D constant; the 2D one is
// what makes the expectation over the surface equal D, Eq. 2), Sigma_a = d (alpha* A*^-1)^2 (Algorithm 1
// line 12), Sigma_s = f^2 J J^T (line 11), points of the implicit 4D grid (Sec. 3.3.1) at two
// levels blended by the mollified roulette R of Eq. 8, and C the analytic compensation of Eq. 9-10.
// Defaults follow the authors' published shader where the paper is vague (docs/kemppinen2025.md): d = pi D(h) in
// Sigma_a (their Jacobian determinant; Algorithm 1 returns d / pi times the sum, i.e. D(h) times it, as here) and
// their LOD, log2(f max|J_i| sqrt(N)) + 2^f. `angular_covariance=d` and `lod=cells` keep our earlier reading.
#include "glints/kemppinen2025/kemppinen2025_core.glsl"

// Per-glint colours: lighting.frag uses glintColorD (RGB NDF) instead of glintD when this is defined.
#define GLINT_COLOR_D 1

// Footprint cells: the finer of the two levels has spatial cells between KAPPA and 2 KAPPA filter standard
// deviations (major axis), the coarser between 2 KAPPA and 4 KAPPA, so the 2x2 spatial neighbourhood (which
// covers at least half a cell around x) holds the filter (Sec. 3.3.2: "footprint covering 1-2 spatial cells").
const float KEMPPINEN_KAPPA = 3.0;
const float KEMPPINEN_MAX_LEVEL = 24.0;

// One point process (one per triplanar plane, Sec. 3.3.6; one with UVs).
struct KemppinenProcess {
    float weight;          // triplanar blend weight (1 with UVs)
    float spatialNorm;     // 1 / (2 pi sqrt(det Sigma_s)), Sigma_s in x_s units
    vec3 invCov;           // Sigma_s^-1 = [x y; y z], x_s units
    int level;             // floor(lambda)
    float levelFrac;       // lambda - floor(lambda): weight of level + 1
    ivec2 baseCell[2];     // lower-left cell of the 2x2 spatial neighbourhood, per level
    vec2 local[2];         // x_s res_s - baseCell, per level (cell units, avoids cancellation with large UVs)
    vec3 invCovCell[2];    // Sigma_s^-1 / res_s^2: the inverse covariance in cell units, per level
};

struct GlintPixel {
    bool hasGlints;        // density > 0
    vec2 alpha;            // (alpha_x, alpha_y): material alpha split by the roughness anisotropy
    vec2 angularStretch;   // A*^-1 diagonal (glint anisotropy)
    float invDensity;      // 1 / N
    float microRoughness;
    int processCount;
    int neighbourSide;     // 2 (k = 4) or 4 (k = 16)
    float colorVariation;
    float footprintAnisotropy;
    KemppinenProcess process[3];
};

// Counts Gaussian-pair evaluations of the current pixel (read by glintExtraAOV after the light loop).
int kemppinenGaussianCount = 0;

// Builds the process for spatial coordinates x_s = A uv with UV Jacobian columns (dx, dy).
KemppinenProcess kemppinenProcess(vec2 uv, vec2 dx, vec2 dy, vec2 stretch, float resolution, float weight,
                                  out float anisotropy) {
    KemppinenProcess p;
    p.weight = weight;
    vec2 xs = stretch * uv;
    vec2 jx = stretch * dx, jy = stretch * dy;
    float f2 = P_FILTER_SIZE * P_FILTER_SIZE;
    // Sigma_s = f^2 J J^T (Algorithm 1 line 11), with a floor of 1e-4 level-0 cells so it stays invertible.
    float floorVar = 1e-8 / (resolution * resolution);
    float a0 = f2 * (jx.x * jx.x + jy.x * jy.x), c0 = f2 * (jx.y * jx.y + jy.y * jy.y);
    float a = a0 + floorVar;
    float b = f2 * (jx.x * jx.y + jy.x * jy.y);
    float c = c0 + floorVar;
    // det = a c - b^2 without its cancellation: a0 c0 - b^2 = f^4 (jx x jy)^2 exactly, so a nearly degenerate
    // footprint (parallel derivatives, thousands of UV units long at grazing angles) keeps a positive determinant
    // instead of rounding to zero or below (which made the inverse infinite and D NaN).
    float cross2 = jx.x * jy.y - jx.y * jy.x;
    float det = max(f2 * f2 * cross2 * cross2 + floorVar * (a0 + c0) + floorVar * floorVar, 1e-30);
    p.invCov = vec3(c, -b, a) / det;
    p.spatialNorm = 1.0 / (2.0 * PI * sqrt(det));
    float mean = 0.5 * (a + c), diff = 0.5 * (a - c);
    float root = sqrt(diff * diff + b * b);
    float major = sqrt(mean + root), minor = sqrt(det) / major;   // minor^2 major^2 = det: no cancellation either
    anisotropy = major / minor;
    // Sec. 3.3.2 / Algorithm 1 line 5 (QueryLod): the level from the footprint size in grid units. authors (their
    // shader): log2(f max|J_i| sqrt(N)) + 2^f, about one level below `cells` at f = 0.7 (finer spatial cells,
    // coarser angular ones: a smaller share of the NDF from the compensation). cells (our earlier reading):
    // spatial cells of 3-6 filter deviations along the major axis, so the 2x2 neighbourhood holds the filter.
    float lambda = P_LOD < 0.5 ? log2(P_FILTER_SIZE * max(length(jx), length(jy)) * resolution) + exp2(P_FILTER_SIZE)
                               : log2(2.0 * KEMPPINEN_KAPPA * major * resolution);
    lambda = clamp(lambda, 0.0, KEMPPINEN_MAX_LEVEL);
    p.level = int(floor(lambda));
    p.levelFrac = lambda - float(p.level);
    for (int i = 0; i < 2; ++i) {
        float resS = resolution * exp2(-float(p.level + i));
        vec2 cellCoord = xs * resS;
        p.baseCell[i] = ivec2(floor(cellCoord - 0.5));
        p.local[i] = cellCoord - vec2(p.baseCell[i]);
        p.invCovCell[i] = p.invCov / (resS * resS);
    }
    return p;
}

// A point of the surface's tangent plane seen through a pixel position (for triplanar footprints: position
// derivatives are not in the G-buffer, and a full-screen pass cannot take them).
vec3 kemppinenTangentPlanePoint(vec2 pixelPosition, vec3 planePoint, vec3 planeNormal) {
    vec2 ndc = pixelPosition / vec2(u_viewport.xy) * 2.0 - 1.0;
    vec4 p = u_inverseViewProjection * vec4(ndc, 0.5, 1.0);
    vec3 dir = p.xyz / p.w - u_cameraPosition.xyz;
    float denom = dot(dir, planeNormal);
    denom = abs(denom) > 1e-8 ? denom : 1e-8;
    return u_cameraPosition.xyz + dir * (dot(planePoint - u_cameraPosition.xyz, planeNormal) / denom);
}

GlintPixel glintSetup(GlintSurface s) {
    GlintPixel px;
    float density = P_DENSITY * s.densityScale;   // spatially varying density (texture channel x material)
    px.hasGlints = density > 0.0;
    density = max(density, 1e-6);
    float resolution = sqrt(density);              // Algorithm 1 line 1 (det A* = 1 here)
    px.invDensity = 1.0 / density;
    float rough = sqrt(P_ROUGHNESS_ANISOTROPY);
    px.alpha = max(vec2(s.alpha * rough, s.alpha / rough), vec2(1e-4));
    // Sigma_a = d (alpha* A*^-1)^2: with d = pi D(h) (authors' code) the lobe is sqrt(pi) wider than with D(h).
    // Folded into alpha* here so evaluation and sampling (kemppinen2025_sampling.glsl) share it.
    px.microRoughness = P_MICRO_ROUGHNESS * (P_ANGULAR_COVARIANCE < 0.5 ? sqrt(PI) : 1.0);
    px.neighbourSide = P_NEIGHBORS > 0.5 ? 4 : 2;
    px.colorVariation = P_COLOR_VARIATION;
    bool triplanar = P_TRIPLANAR > 0.5;
    // Sec. 3.3.6 anisotropy: A* = diag(1/sqrt(a), sqrt(a)) (det 1, so the density per UV area is unchanged):
    // the UV grid is stretched and the angular lobe inversely stretched, widest along the tangent.
    float an = sqrt(P_GLINT_ANISOTROPY);
    vec2 stretch = triplanar ? vec2(1.0) : vec2(1.0 / an, an);
    px.angularStretch = 1.0 / stretch;
    px.footprintAnisotropy = 1.0;
    if (!triplanar) {
        px.processCount = 1;
        px.process[0] = kemppinenProcess(s.uv, s.duvdx, s.duvdy, stretch, resolution, 1.0, px.footprintAnisotropy);
    } else {
        // Sec. 3.3.6 UV-free mode: three point processes in the world planes x, y, z, blended with weights
        // |n . e_q| (normalised) through the same roulette as the levels. Footprints from the tangent plane.
        px.processCount = 3;
        vec2 centre = vec2(s.pixel) + 0.5;
        vec3 p0 = kemppinenTangentPlanePoint(centre, s.position, s.n);
        vec3 dPdx = kemppinenTangentPlanePoint(centre + vec2(1.0, 0.0), s.position, s.n) - p0;
        vec3 dPdy = kemppinenTangentPlanePoint(centre + vec2(0.0, 1.0), s.position, s.n) - p0;
        vec3 w = abs(s.n);
        w /= max(w.x + w.y + w.z, 1e-6);
        float unused;
        px.process[0] = kemppinenProcess(s.position.yz, dPdx.yz, dPdy.yz, stretch, resolution, w.x, unused);
        px.process[1] = kemppinenProcess(s.position.xz, dPdx.xz, dPdy.xz, stretch, resolution, w.y, px.footprintAnisotropy);
        px.process[2] = kemppinenProcess(s.position.xy, dPdx.xy, dPdy.xy, stretch, resolution, w.z, unused);
    }
    return px;
}

// Per-light, per-level quantities shared by the cells of one level (Algorithm 1 lines 8-12).
struct KemppinenLevel {
    int level, process;
    float weight;          // w_lambda x triplanar weight
    ivec2 baseCell;        // spatial 2x2 neighbourhood
    vec2 local;
    vec3 invCovS;          // Sigma_s^-1 in spatial cell units
    vec2 xaCell;           // x_a' in angular cell units
    ivec2 cellsA;          // angular cells of the (stretched) unit square
    vec2 cellToPrior;      // angular cell units -> x_a
    float invVarA;         // 1 / sigma'^2 in angular cell units
};

// The points of one angular cell in the 2x2 spatial neighbourhood (Algorithm 1 lines 13-19).
vec3 kemppinenCellTerms(KemppinenLevel lv, ivec2 cellA, float colorVariation) {
    vec3 sum = vec3(0.0);
    bool valid = all(greaterThanEqual(cellA, ivec2(0))) && all(lessThan(cellA, lv.cellsA));
    vec2 da0 = lv.xaCell - vec2(cellA);
    for (int si = 0; si < 4; ++si) {
        ivec2 offset = ivec2(si & 1, si >> 1);
        KemppinenPoint p = kemppinenPoint(lv.baseCell + offset, cellA, lv.level, lv.process);   // lines 15-18
        vec2 fromCentre = (vec2(cellA) + p.angular) * lv.cellToPrior - 0.5;
        bool inDisk = dot(fromCentre, fromCentre) < 0.25;     // points outside U are rejected
        vec2 ds = lv.local - vec2(offset) - p.spatial;
        vec2 da = da0 - p.angular;
        // The quadratic form is >= 0; with a nearly singular Sigma_s its float rounding is not (exp would overflow).
        float e = max(ds.x * ds.x * lv.invCovS.x + 2.0 * ds.x * ds.y * lv.invCovS.y + ds.y * ds.y * lv.invCovS.z, 0.0) +
                  dot(da, da) * lv.invVarA;
        float weight = (valid && inDisk) ? kemppinenRoulette(p.roulette, lv.weight) * exp(-0.5 * e) : 0.0;
        // line 19 (colour only when asked: three cosines per point otherwise wasted)
        sum += colorVariation > 0.0 ? weight * kemppinenGlintColor(p.hue, colorVariation) : vec3(weight);
    }
    kemppinenGaussianCount += 4;
    return sum;
}

// Explicit sum and compensation of one point process at both levels (lines 7-20).
void kemppinenProcessSum(KemppinenProcess proc, int q, int side, float colorVariation,
                         vec2 xaPrime, vec2 extent, float sigmaIso, float squareMass, inout vec3 explicitSum,
                         inout float compensation) {
    vec3 processSum = vec3(0.0);
    for (int li = 0; li < 2; ++li) {                                  // line 7: levels floor and ceil
        KemppinenLevel lv;
        lv.level = proc.level + li;
        lv.process = q;
        lv.weight = (li == 0 ? 1.0 - proc.levelFrac : proc.levelFrac) * proc.weight;   // line 8
        lv.baseCell = proc.baseCell[li];
        lv.local = proc.local[li];
        float resA = exp2(float(lv.level));                           // line 10
        lv.cellsA = ivec2(ceil(extent * resA));
        lv.xaCell = xaPrime * resA;
        lv.cellToPrior = 1.0 / (resA * extent);
        lv.invVarA = 1.0 / (sigmaIso * sigmaIso * resA * resA);
        lv.invCovS = proc.invCovCell[li];   // per pixel (line 9: res_s = sqrt(N) 2^-l)
        // Line 14: the k nearest angular cells, a side x side block around x_a'.
        ivec2 a0 = ivec2(floor(lv.xaCell - (0.5 * float(side) - 0.5)));
        // Eq. 10, second integral: B(k) clipped to the square; the compensation C of Eq. 9, blended linearly.
        vec2 lo = max(vec2(a0) / resA, vec2(0.0));
        vec2 hi = min(vec2(a0 + side) / resA, extent);
        float blockMass = kemppinenIntervalMass(xaPrime.x, sigmaIso, lo.x, hi.x) *
                          kemppinenIntervalMass(xaPrime.y, sigmaIso, lo.y, hi.y);
        compensation += lv.weight * max(squareMass - blockMass, 0.0);
        // Constant loop bounds per branch, so the compiler unrolls them.
        if (side == 2) {
            for (int j = 0; j < 2; ++j)
                for (int i = 0; i < 2; ++i) processSum += kemppinenCellTerms(lv, a0 + ivec2(i, j), colorVariation);
        } else {
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) processSum += kemppinenCellTerms(lv, a0 + ivec2(i, j), colorVariation);
        }
    }
    explicitSum += processSum * proc.spatialNorm;
}

// D*^f(x, h) in RGB (Algorithm 1). h: shading-frame half vector.
vec3 kemppinenFilteredNdf(GlintPixel px, vec3 h, int ndf) {
    if (!px.hasGlints || h.z <= 0.0) return vec3(0.0);
    float d = kemppinenSmoothD(h, px.alpha, ndf);                       // line 4
    // Where D underflows (Beckmann tails) no facet exists in practice; the lobe width alpha* sqrt(D) would
    // reach 0 and the normalisations infinity, so stop here (NaN must never reach the framebuffer).
    if (d < 1e-20) return vec3(0.0);
    vec2 xa = kemppinenToPrior(h, px.alpha, ndf);                       // line 3
    // Line 12: Sigma_a = d (alpha* A*^-1)^2 (d's pi is in px.microRoughness). The angular grid lives in the inversely stretched angular space
    // x_a' = x_a / A*^-1 (Sec. 3.3.6, "inversely stretching the angular space"), where the lobe is isotropic
    // (sigma' = alpha* sqrt(d)) so the k nearest cells hold it in both directions; with A* = I it is x_a.
    // (Our reading: Algorithm 1 keeps an isotropic grid, whose 2x2 window cannot hold a 16:1 lobe.)
    vec2 sigmaA = px.microRoughness * sqrt(d) * px.angularStretch;
    float sigmaIso = px.microRoughness * sqrt(d);
    vec2 extent = 1.0 / px.angularStretch;                             // the unit square in x_a'
    vec2 xaPrime = xa * extent;
    float angularNorm = 1.0 / (2.0 * PI * sigmaA.x * sigmaA.y);
    // Eq. 10, first integral: the Gaussian's mass over the unit square enclosing U.
    float squareMass = kemppinenIntervalMass(xa.x, sigmaA.x, 0.0, 1.0) * kemppinenIntervalMass(xa.y, sigmaA.y, 0.0, 1.0);
    vec3 explicitSum = vec3(0.0);
    float compensation = 0.0;
    kemppinenProcessSum(px.process[0], 0, px.neighbourSide, px.colorVariation, xaPrime, extent, sigmaIso,
                        squareMass, explicitSum, compensation);
    for (int q = 1; q < px.processCount; ++q)   // triplanar (Sec. 3.3.6): the two other planes
        kemppinenProcessSum(px.process[q], q, px.neighbourSide, px.colorVariation, xaPrime, extent,
                            sigmaIso, squareMass, explicitSum, compensation);
    // Eq. 11; the compensation uses the mean glint colour, which is white (kemppinenGlintColor).
    return d * (explicitSum * (angularNorm * px.invDensity) + vec3(compensation));
}

vec3 glintColorD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    return kemppinenFilteredNdf(px, h, s.ndf);
}

float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    return dot(kemppinenFilteredNdf(px, h, s.ndf), vec3(1.0 / 3.0));
}

vec4 glintFootprintAOV(GlintPixel px, GlintSurface s) {
    int q = px.processCount == 3 ? 1 : 0;
    return vec4(px.footprintAnisotropy, float(px.process[q].level) + px.process[q].levelFrac,
                float(px.process[q].level), px.process[q].levelFrac);
}

// x: Gaussian-pair evaluations in this pixel (all lights), y: LOD lambda, z: density, w: process count.
vec4 glintExtraAOV(GlintPixel px, GlintSurface s) {
    return vec4(float(kemppinenGaussianCount), float(px.process[0].level) + px.process[0].levelFrac,
                1.0 / px.invDensity, float(px.processCount));
}
