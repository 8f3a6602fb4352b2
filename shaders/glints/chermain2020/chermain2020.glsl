// Chermain, Sauvage, Dischler, Dachsbacher 2020, "Procedural Physically based BRDF for Real-Time Rendering of
// Glints" (CGF 39(7)), with the options of Chermain, Lucas, Sauvage, Dischler, Dachsbacher 2021, "Real-Time
// Geometric Glint Anti-Aliasing with Normal Map Filtering" (PACMCGIT 4(1)). Interface: shaders/glints/README.md.
// Facts the papers leave vague come from the authors' MIT code (ASTex-ICube/real_time_glint, shader/glint.frag.glsl;
// ASTex-ICube/aa_real_time_glint, improved_glint_envmap.frag.glsl); deviations are listed in docs/chermain2020.md.
//
// 2020, Eq. 1, 6: the NDF in slope space, D(h) = P22(m) / cos^4(theta_h), m = -h.xy / h.z.
// 2020, Alg. 1 (Eq. 14): the P-NDF of a pixel is the footprint-weighted mean of the NDFs of the cells of a
//   multiscale grid (a MIP pyramid of 2^(L-1) x 2^(L-1) cells per unit UV at level 0); the level follows the
//   footprint's minor axis (l = L - 1 + log2(minor)) and the two bracketing levels are blended linearly (a blend of
//   normalized NDFs is normalized).
// 2020, Alg. 2: the cells of one level are weighted by pbrt's EWA Gaussian (Heckbert 1989) over the footprint
//   ellipse, regularized by one cell.
// 2020, Alg. 3, Eq. 8-11: each cell holds n = density x cell area microfacets; its NDF is the product of
//   two 1D marginals of dictionary level l_dist = round(log4 n + zeta N(0, 1)) (density randomization), picked at
//   random, rotated by a random angle and scaled from the dictionary's roughness to the material's; a cell at
//   l_dist = L is the smooth NDF; a cell is empty with probability 1 - microfacet relative area (Alg. 3 line 4).
// 2021, Eq. 18: the scaling is the whitening of a correlated anisotropic Gaussian (sigma_x, sigma_y, rho).
// 2021, geometric glint anti-aliasing (GGAA, the paper's first contribution): the pixel's range of half vectors is carried into the dictionary's slope space by the same
//   transform, and the marginals are looked up with the hardware's filtered textureGrad (`anti_aliasing`).
// 2021, normal map filtering: LEAN mapping (Olano & Baker 2010): the normal map's filtered slope covariance (the G-buffer's, read
//   as GlintSurface.slopeCovariance) is added to the material's (`normal_filtering`).
// GGX (ours; the papers' base NDF is Beckmann, the dictionary's lobes are Gaussian): the half vector's slope is
//   warped radially so that the Gaussian the cells converge to becomes GGX's Student-t (glintD); smooth cells are
//   GGX itself.
// Per pixel (glintSetup): the footprint, the two levels, their ellipses and row ranges, the shape (sigma, rho).
// Per light (glintD): the slope in the target's whitened space, once; then the cells of both levels (each: one
// hash, one rotation, two dictionary lookups).
// Extended lights (shaders/glints/README.md, "Extended lights"): the papers' lights are points. The light's size
// (g_glintLight) is not read: point, spot and directional lights are evaluated at their direction, and an area light
// takes the lighting pass's fallback, glintD at its centre's half vector over D_smooth there times its smooth LTC
// specular (no GLINT_AREA_LIGHTS).
#include "glints/chermain2020/chermain2020_dictionary.glsl"

const int CHERMAIN_MAX_CELLS_PER_LEVEL = 128;   // guard (authors: 100 iterations of the bounding box)
// The cells' draws (Alg. 3 lines 1-18 do not depend on the light) are made once per pixel and kept for every light
// when the two levels hold at most this many non-empty cells (isotropic footprints: 10-22); a level with more is
// drawn again per light (elongated footprints).
const int CHERMAIN_CACHED_CELLS = 24;
const float CHERMAIN_MAX_NORMAL = 5.4;          // largest |N(0, 1)| the 24-bit uniforms below can give

struct ChermainLevel {
    int level;        // pyramid level: 2^(L-1-level) cells per unit (stretched) UV
    float log4n;      // log4 of the microfacets per cell (Alg. 3 lines 5-6), density scale included
    vec2 st;          // footprint centre in the level's cell coordinates (cell centres at integers)
    vec3 ellipse;     // EWA quadratic form A ss^2 + B ss tt + C tt^2 < 1 (Alg. 2)
    ivec2 rows;       // first and last row of the ellipse's bounding box
    bool allSmooth;   // every cell of the level is at l_dist = L: the level's P22 is the smooth one
    int firstCached;  // the level's draws in GlintPixel.cells[firstCached, firstCached + cached)
    int cached;       // -1: not cached (more cells than the cache holds), drawn per light
    float sumWeights; // of every cell of the level (empty ones included)
};

// One cell's draw (Alg. 3): not stored when the cell is empty.
struct ChermainCell {
    bool empty;
    int lDist;         // dictionary level, CHERMAIN_LEVELS = the smooth NDF
    int i, j;          // the two marginals
    float ct, sn;      // cos and sin of the random rotation
    float scale;       // 1 / the probability that the cell holds microfacets (lobe_count = material): E[D] kept
};

struct GlintPixel {
    ChermainLevel levels[2];
    vec4 cells[CHERMAIN_CACHED_CELLS];   // EWA weight x scale, cos, sin, lDist + 256 i + 65536 j (exact in float)
    float blend;        // weight of levels[1] (Alg. 1 line 7)
    bool noFootprint;   // zero footprint: the smooth NDF (authors' code)
    bool noFacets;      // density scale <= 0: no microfacets, no specular reflection
    vec3 shape;         // sigma_x, sigma_y, rho of the target slope distribution (2021 Eq. 18, LEAN included)
    vec4 footprint;     // anisotropy (after the clamp), LOD l, log4 n at the finer level, level blend
};

// Debug counters for --aov extra: cells evaluated and glintD calls of this pixel.
int g_chermainCells = 0;
int g_chermainLightCalls = 0;

// A 4D integer hash (PCG-style: an LCG step, then two rounds of cross-lane multiplies and an xorshift).
// Inputs are integer bit patterns (never uint(negative float)).
uvec4 chermainHash4(uvec4 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
    v ^= v >> 16u;
    v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
    return v;
}

// Inverse of the standard normal CDF (Acklam's rational approximation, relative error < 1.2e-9): the density
// randomization of Alg. 3 line 8 samples N(l_dist, zeta) by inversion, like the authors' erfinv.
float chermainProbit(float p) {
    const float plow = 0.02425;
    if (p < plow || p > 1.0 - plow) {
        float q = sqrt(-2.0 * log(p < plow ? p : 1.0 - p));
        float x = (((((-7.784894002430293e-03 * q - 3.223964580411365e-01) * q - 2.400758277161838e+00) * q -
                     2.549732539343734e+00) * q + 4.374664141464968e+00) * q + 2.938163982698783e+00) /
                  ((((7.784695709041462e-03 * q + 3.224671290700398e-01) * q + 2.445134137142996e+00) * q +
                    3.754408661907416e+00) * q + 1.0);
        return p < plow ? x : -x;
    }
    float q = p - 0.5, r = q * q;
    return (((((-3.969683028665376e+01 * r + 2.209460984245205e+02) * r - 2.759285104469687e+02) * r +
              1.383577518672690e+02) * r - 3.066479806614716e+01) * r + 2.506628277459239e+00) * q /
           (((((-5.447609879822406e+01 * r + 1.615858368580409e+02) * r - 1.556989798598866e+02) * r +
              6.680131188771972e+01) * r - 1.328068155288572e+01) * r + 1.0);
}

// The target slope distribution P22 (2021 Eq. 18: a correlated anisotropic Gaussian for Beckmann; the Student-t
// with 2 degrees of freedom of the same scale for GGX), q = m^T Sigma^-1 m.
float chermainTargetP22(vec2 m, vec3 shape, int ndf) {
    float sx = shape.x, sy = shape.y, rho = shape.z, c = 1.0 - rho * rho;
    float q = (m.x * m.x / (sx * sx) - 2.0 * rho * m.x * m.y / (sx * sy) + m.y * m.y / (sy * sy)) / c;
    float norm = 1.0 / (2.0 * PI * sx * sy * sqrt(c));
    if (ndf == NDF_BECKMANN) return norm * exp(-0.5 * q);
    float t = 1.0 + 0.5 * q;
    return norm / (t * t);
}

// Alg. 2 set-up of one level: the footprint (derivatives d0, d1 of the stretched UV st) in the level's cells,
// the EWA ellipse with one cell of regularization (pbrt MIPMap::EWA), and the rows of its bounding box.
ChermainLevel chermainSetupLevel(int level, vec2 st, vec2 d0, vec2 d1, float log4nLevel0) {
    ChermainLevel lv;
    lv.level = level;
    lv.log4n = log4nLevel0 + float(level);   // a cell of level l holds 4^l cells of level 0
    lv.firstCached = 0;
    lv.cached = 0;
    lv.sumWeights = 0.0;
    float cellsPerUnit = exp2(float(CHERMAIN_LEVELS - 1 - level));
    lv.st = st * cellsPerUnit - 0.5;
    d0 *= cellsPerUnit;
    d1 *= cellsPerUnit;
    float A = d0.y * d0.y + d1.y * d1.y + 1.0;
    float B = -2.0 * (d0.x * d0.y + d1.x * d1.y);
    float C = d0.x * d0.x + d1.x * d1.x + 1.0;
    float invF = 1.0 / (A * C - 0.25 * B * B);
    A *= invF;
    B *= invF;
    C *= invF;
    lv.ellipse = vec3(A, B, C);
    float det = 4.0 * A * C - B * B;
    float halfHeight = 2.0 * sqrt(A * det) / det;
    lv.rows = ivec2(int(ceil(lv.st.y - halfHeight)), int(floor(lv.st.y + halfHeight)));
    // Every cell smooth: even the largest negative deviate keeps l_dist >= L - 0.5 (then round() gives L), and no
    // cell is emptied by the relative area (an empty cell contributes 0, not the smooth NDF).
    lv.allSmooth = lv.log4n - P_DENSITY_RANDOMIZATION * CHERMAIN_MAX_NORMAL >= float(CHERMAIN_LEVELS) - 0.5 &&
                   P_MICROFACET_RELATIVE_AREA >= 1.0;
    return lv;
}

void chermainDrawLevels(inout GlintPixel px);   // below: Alg. 2-3, the cells' draws

GlintPixel glintSetup(GlintSurface s) {
    GlintPixel px;
    // --- Shape (2021 Eq. 18): the material's sigma = alpha / sqrt 2 per axis (roughness_anisotropy = alpha_x /
    // alpha_y at alpha_x alpha_y = alpha^2), its correlation rho, plus the normal map's filtered slope covariance
    // (LEAN, 2021 normal map filtering) when normal_filtering is on. Clamps as the authors' (sigma in [0.01, 1]).
    float ratio = sqrt(max(P_ROUGHNESS_ANISOTROPY, 1e-3));
    float sx = s.alpha * ratio * 0.70710678, sy = s.alpha / ratio * 0.70710678;
    float rho = clamp(P_SLOPE_CORRELATION, -0.99, 0.99);
    if (P_NORMAL_FILTERING > 0.5) {
        vec3 cov = s.slopeCovariance;   // Sigma_xx, Sigma_yy, Sigma_xy of the normal map's slopes (0 without one)
        float vx = sx * sx + clamp(cov.x, 0.0, 1.0), vy = sy * sy + clamp(cov.y, 0.0, 1.0);
        float cxy = rho * sx * sy + (P_NORMAL_FILTERING < 1.5 ? cov.z : 0.0);   // 2: "LEAN without rho"
        sx = sqrt(vx);
        sy = sqrt(vy);
        rho = clamp(cxy / (sx * sy), -0.99, 0.99);
    }
    px.shape = vec3(clamp(sx, 0.005, 1.0), clamp(sy, 0.005, 1.0), rho);

    // --- Alg. 1 lines 3-5 (pbrt MIPMap::Lookup): the longer derivative is the major axis; an eccentricity above
    // max_anisotropy widens the minor one. Anisotropic glints (ours, after the authors' "texCoord *= vec2(1000, 1)"
    // comment): UV v is stretched by glint_anisotropy, so cells (and glints) are that much longer along u.
    vec2 stretch = vec2(1.0, max(P_GLINT_ANISOTROPY, 1.0));
    vec2 st = s.uv * stretch, d0 = s.duvdx * stretch, d1 = s.duvdy * stretch;
    if (dot(d0, d0) < dot(d1, d1)) { vec2 t = d0; d0 = d1; d1 = t; }
    float major = length(d0), minor = length(d1);
    if (minor * P_MAX_ANISOTROPY < major && minor > 0.0) {
        float k = major / (minor * P_MAX_ANISOTROPY);
        d1 *= k;
        minor *= k;
    }
    px.noFacets = !(s.densityScale > 0.0);
    px.noFootprint = !(minor > 0.0) || isinf(minor);
    // --- Alg. 1 lines 6-7: the level of the minor axis (lod_bias: Unreal's r.Substrate.Glints.LevelBias analogue),
    // its integer part and the blend to the next level.
    float l = clamp(float(CHERMAIN_LEVELS - 1) + log2(max(minor, 1e-30)) + P_LOD_BIAS, 0.0, 100.0);
    int il = int(floor(l));
    px.blend = l - float(il);
    // Alg. 3 lines 5-6: microfacets per cell of level 0, density per unit UV area x the cell's UV area
    // (2^-(L-1) squared, divided by the stretch), x the material's density scale (mask), as log base 4.
    float lnN0 = P_LOG_DENSITY + log(max(s.densityScale, 1e-30)) - log(stretch.y) -
                 2.0 * float(CHERMAIN_LEVELS - 1) * 0.69314718;
    float log4n0 = lnN0 / 1.38629436;
    // lobe_count = material (ours, docs/chermain2020.md deviation 16): a glint narrower than the dictionary's lobe
    // (glint_angle below sigma_lobe in dictionary slopes, see chermainCellP22) cannot be drawn; instead the cells
    // hold (s / sigma_lobe)^2 fewer lobes, so that the expected number of lobes that reflect a given h (count x
    // area) and the share each carries stay the material's. s at h = n: gamma / sqrt 2 times the whitening's
    // scale sigma_dict / sqrt(sigma_x sigma_y sqrt(1 - rho^2)) (the GGX warp is the identity there).
    if (P_LOBE_COUNT > 0.5 && P_GLINT_ANGLE > 0.0) {
        float sd2 = 0.5 * P_GLINT_ANGLE * P_GLINT_ANGLE * CHERMAIN_SIGMA_DICT * CHERMAIN_SIGMA_DICT /
                    (px.shape.x * px.shape.y * sqrt(1.0 - px.shape.z * px.shape.z));
        log4n0 += min(0.0, log(sd2 / (CHERMAIN_LOBE_STD * CHERMAIN_LOBE_STD)) / 1.38629436);
    }
    px.levels[0] = chermainSetupLevel(il, st, d0, d1, log4n0);
    px.levels[1] = chermainSetupLevel(il + 1, st, d0, d1, log4n0);
    // With one light the cells are drawn where glintD evaluates them (caching them costs 7-10 % more there); with
    // more, once here (u_exposure.y: the frame's light count; 0 in the probes).
    px.levels[0].cached = px.levels[1].cached = -1;
    if (!px.noFootprint && !px.noFacets && u_exposure.y > 1.5) chermainDrawLevels(px);
    px.footprint = vec4(minor > 0.0 ? major / minor : 1.0, l, px.levels[0].log4n, px.blend);
    return px;
}

// What glintD computes once per light and every cell reuses: the half vector's slope in the whitened (and, for
// GGX, warped) space u of the target distribution, its screen derivatives there, the Jacobian of m -> dictionary
// slope (without the rotation, whose determinant is 1) and the smooth P22 at m.
struct ChermainSlope {
    vec2 u;             // slope in the standard-normal space of the target (2021 Eq. 18; GGX warped, see below)
    vec2 dudx, dudy;    // its derivatives x kernel / range (2021 GGAA), in the dictionary's texture coordinates
    float jacobian;     // |d(dictionary slope) / dm| = sigma_dict^2 |W| |T|
    float smoothP22;    // the target P22 at m: a cell at l_dist = L
    bool filtered;
};

// Alg. 3 lines 1-18 for the cell `cell` of a level: what it draws (independent of the light).
ChermainCell chermainDrawCell(ChermainLevel lv, ivec2 cell) {
    ChermainCell c;
    // Eq. 8, Alg. 3 line 1: the coherent index. A cell is seeded by its first level-0 cell, so it keeps the random
    // numbers of one of its children across a level transition (the hash has no level in it).
    uvec2 first = uvec2(cell) << uint(min(lv.level, 31));
    uvec4 r = chermainHash4(uvec4(first, floatBitsToUint(P_SEED), 0x9e3779b9u));
    // Alg. 3 lines 3-4: an empty cell with probability 1 - relative area.
    float uArea = (float(r.x & 0xffffu) + 0.5) * (1.0 / 65536.0);
    c.empty = uArea > P_MICROFACET_RELATIVE_AREA;
    // Alg. 3 lines 7-9: the dictionary level, randomized around log4 n (zeta = density_randomization), rounded.
    float uDensity = (float(r.y >> 8u) + 0.5) * (1.0 / 16777216.0);
    float lf = lv.log4n + P_DENSITY_RANDOMIZATION * chermainProbit(uDensity);
    // The authors clamp l_dist at 0: a cell with fewer than one microfacet still holds 4 lobes. lobe_count =
    // material (ours, deviation 16): such a cell holds level 0's 4 lobes with probability 4^lf and none
    // otherwise, which keeps the expected lobe count 4^(lf + 1) and lets sparse materials have dark pixels.
    // Each kept cell weighs 1 / 4^lf: it stands for the area of the empty ones, as a facet of a sparse material
    // stands for the surface around it (the mean of D stays the smooth NDF's).
    c.scale = 1.0;
    if (P_LOBE_COUNT > 0.5 && lf < 0.0) {
        float keep = exp2(2.0 * lf);
        c.empty = c.empty || (float(r.w >> 8u) + 0.5) * (1.0 / 16777216.0) > keep;
        c.scale = 1.0 / keep;
    }
    c.lDist = int(clamp(round(lf), 0.0, float(CHERMAIN_LEVELS)));
    // Alg. 3 lines 13-15: the cell's random rotation (against glint alignment).
    float theta = 2.0 * PI * (float(r.x >> 16u) + 0.5) * (1.0 / 65536.0);
    c.ct = cos(theta);
    c.sn = sin(theta);
    // Alg. 3 lines 17-18: the two marginals of the cell.
    c.i = int(((r.z & 0xffffu) * uint(CHERMAIN_MARGINALS)) >> 16u);
    c.j = int(((r.z >> 16u) * uint(CHERMAIN_MARGINALS)) >> 16u);
    return c;
}

// Alg. 3 lines 10-19: the NDF in slope space of a non-empty cell.
float chermainCellP22(ChermainSlope sl, ChermainCell c) {
    // Alg. 3 lines 10-11: beyond the dictionary the cell is the smooth distribution.
    if (c.lDist == CHERMAIN_LEVELS) return sl.smoothP22;
    // Alg. 3 line 16: the slope rotated by the cell's angle, in the dictionary's scale.
    mat2 invR = mat2(c.ct, -c.sn, c.sn, c.ct);
    vec2 a = abs(CHERMAIN_SIGMA_DICT * (invR * sl.u));   // the marginals are even
    if (a.x >= CHERMAIN_RANGE || a.y >= CHERMAIN_RANGE) return 0.0;
    vec2 t = a * (1.0 / CHERMAIN_RANGE);
    // glint_angle (ours, the glint material's gamma): a lobe of the dictionary is sigma_lobe wide in dictionary
    // slopes. A wider glint (a cone of half-angle gamma holds the area of a Gaussian of deviation gamma / sqrt 2) is
    // read from the table's box-filtered mips: a box of width sqrt(12 (s^2 - sigma_lobe^2)) adds the missing
    // variance. Glints narrower than the table's lobes are not possible.
    float widen = 0.0;
    if (P_GLINT_ANGLE > 0.0) {
        float sd = P_GLINT_ANGLE * 0.70710678 * sqrt(sl.jacobian);   // gamma / sqrt 2 in dictionary slopes
        float extra = sd * sd - CHERMAIN_LOBE_STD * CHERMAIN_LOBE_STD;
        widen = extra > 0.0 ? sqrt(12.0 * extra) / CHERMAIN_RANGE : 0.0;
    }
    float pi_, pj;
    if (sl.filtered) {
        // 2021 GGAA: the footprint in slope space goes through the same transform as the slope.
        vec2 gx = CHERMAIN_SIGMA_DICT * (invR * sl.dudx), gy = CHERMAIN_SIGMA_DICT * (invR * sl.dudy);
        vec2 gxw = sqrt(gx * gx + widen * widen);
        pi_ = chermainMarginalGrad(c.lDist, c.i, t.x, gxw.x, gy.x);
        pj = chermainMarginalGrad(c.lDist, c.j, t.y, gxw.y, gy.y);
    } else {
        float lod = widen > 0.0 ? log2(max(widen * float(CHERMAIN_TEXELS), 1.0)) : 0.0;
        pi_ = chermainMarginalLod(c.lDist, c.i, t.x, lod);
        pj = chermainMarginalLod(c.lDist, c.j, t.y, lod);
    }
    // Alg. 3 line 19 (Eq. 11): the product, times the Jacobian of the transform (normalized in material slopes).
    return pi_ * pj * sl.jacobian;
}

// Alg. 2: the cells of one level are the integer points inside the footprint's ellipse, weighted by pbrt's EWA
// Gaussian (alpha = 2). The authors scan the ellipse's bounding box with a guard of 100 iterations, which for
// rotated elongated footprints stops before the ellipse is covered; here each row visits only its span inside the
// ellipse (the same cells and weights), with a guard of CHERMAIN_MAX_CELLS_PER_LEVEL cells. The two loops below
// (glintSetup's caching, glintD's uncached levels) visit the same cells in the same order.
#define CHERMAIN_FOR_EACH_CELL(lv, BODY)                                                                   \
    {                                                                                                      \
        float A_ = lv.ellipse.x, B_ = lv.ellipse.y, C_ = lv.ellipse.z;                                     \
        int visited_ = 0;                                                                                  \
        for (int it_ = lv.rows.x; it_ <= lv.rows.y && visited_ < CHERMAIN_MAX_CELLS_PER_LEVEL; ++it_) {   \
            float tt_ = float(it_) - lv.st.y;                                                              \
            float disc_ = B_ * B_ * tt_ * tt_ - 4.0 * A_ * (C_ * tt_ * tt_ - 1.0);                         \
            if (disc_ <= 0.0) continue;                                                                    \
            float root_ = sqrt(disc_);                                                                     \
            int s0_ = int(ceil(lv.st.x + (-B_ * tt_ - root_) / (2.0 * A_)));                               \
            int s1_ = int(floor(lv.st.x + (-B_ * tt_ + root_) / (2.0 * A_)));                              \
            for (int is_ = s0_; is_ <= s1_ && visited_ < CHERMAIN_MAX_CELLS_PER_LEVEL; ++is_) {            \
                float ss_ = float(is_) - lv.st.x;                                                          \
                float r2_ = A_ * ss_ * ss_ + B_ * ss_ * tt_ + C_ * tt_ * tt_;                              \
                if (r2_ >= 1.0) continue;                                                                  \
                float weight = exp(-2.0 * r2_) - 0.13533528;                                               \
                ivec2 cell = ivec2(is_, it_);                                                              \
                ++visited_;                                                                                \
                BODY                                                                                       \
            }                                                                                              \
        }                                                                                                  \
    }

// The per-light P22 of a level: the EWA-weighted mean of its cells' NDFs (from the pixel's cached draws when the
// level was cached, else drawn here).
float chermainLevelP22(GlintPixel px, ChermainLevel lv, ChermainSlope sl) {
    if (lv.allSmooth) return sl.smoothP22;
    float sum = 0.0;
    if (lv.cached >= 0) {
        if (!(lv.sumWeights > 0.0)) return 0.0;
        for (int k = 0; k < lv.cached; ++k) {
            vec4 e = px.cells[lv.firstCached + k];
            int code = int(e.w);
            ChermainCell c = ChermainCell(false, code & 255, (code >> 8) & 255, code >> 16, e.y, e.z, 1.0);   // scale in e.x
            sum += e.x * chermainCellP22(sl, c);
        }
        g_chermainCells += lv.cached;
        return sum / lv.sumWeights;
    }
    float sumWeights = 0.0;
    CHERMAIN_FOR_EACH_CELL(lv, {
        ChermainCell c = chermainDrawCell(lv, cell);
        if (!c.empty) sum += weight * c.scale * chermainCellP22(sl, c);
        sumWeights += weight;
        g_chermainCells += 1;
    })
    return sumWeights > 0.0 ? sum / sumWeights : 0.0;
}

// glintSetup's part of Alg. 2-3 when several lights share it: each level's total EWA weight and the draws of its
// non-empty cells while they fit the cache (a level that overflows it is drawn again per light).
void chermainDrawLevels(inout GlintPixel px) {
    int used = 0;
    for (int k = 0; k < 2; ++k) {
        ChermainLevel lv = px.levels[k];
        lv.firstCached = used;
        lv.cached = 0;
        lv.sumWeights = 0.0;
        float levelWeight = k == 0 ? 1.0 - px.blend : px.blend;
        if (!lv.allSmooth && levelWeight > 0.0) {
            CHERMAIN_FOR_EACH_CELL(lv, {
                lv.sumWeights += weight;
                if (lv.cached >= 0) {
                    ChermainCell c = chermainDrawCell(lv, cell);
                    if (c.empty) {
                    } else if (used < CHERMAIN_CACHED_CELLS) {
                        px.cells[used] = vec4(weight * c.scale, c.ct, c.sn, float(c.lDist + 256 * c.i + 65536 * c.j));
                        ++used;
                        ++lv.cached;
                    } else {
                        used = lv.firstCached;
                        lv.cached = -1;
                    }
                }
            })
        }
        px.levels[k] = lv;
    }
}

// 2021 GGAA: the screen-space derivatives of the half vector in the shading frame, from the surface's
// derivatives (GLINT_SURFACE_DERIVATIVES: position and shading normal one pixel right / up) and the view and
// light distances. The frame turns with the normal (dt = -(t.dn) n, db = -(b.dn) n). Zero when the lighting pass
// provides no derivatives (probes), which makes the filtered lookups plain ones.
void chermainHalfVectorDerivatives(GlintSurface s, vec3 h, vec3 wi, vec3 wo, out vec3 dhx, out vec3 dhy) {
    dhx = vec3(0.0);
    dhy = vec3(0.0);
    if (!(s.viewDistance > 0.0)) return;
    mat3 toWorld = mat3(s.t, s.b, s.n);
    vec3 hw = toWorld * h, iw = toWorld * wi, ow = toWorld * wo;
    float len = length(iw + ow);
    if (!(len > 1e-6)) return;
    for (int k = 0; k < 2; ++k) {
        vec3 dp = k == 0 ? s.dpdx : s.dpdy, dn = k == 0 ? s.dndx : s.dndy;
        vec3 dwo = -(dp - ow * dot(ow, dp)) / s.viewDistance;
        vec3 dwi = g_glintLightDistance > 0.0 ? -(dp - iw * dot(iw, dp)) / g_glintLightDistance : vec3(0.0);
        vec3 dsum = dwo + dwi;
        vec3 dh = (dsum - hw * dot(hw, dsum)) / len;
        float nh = dot(s.n, hw);
        vec3 d = vec3(dot(s.t, dh) - dot(s.t, dn) * nh, dot(s.b, dh) - dot(s.b, dn) * nh, dot(s.n, dh) + dot(dn, hw));
        if (k == 0) dhx = d; else dhy = d;
    }
}

float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    g_chermainLightCalls += 1;
    if (h.z <= 0.0 || px.noFacets) return 0.0;
    vec2 m = -h.xy / h.z;   // Eq. 1
    float cos2 = h.z * h.z, cos4 = cos2 * cos2;
    ChermainSlope sl;
    sl.smoothP22 = chermainTargetP22(m, px.shape, s.ndf);
    if (px.noFootprint) return sl.smoothP22 / cos4;
    // 2021 Eq. 18: W whitens the target Gaussian (sigma_x, sigma_y, rho): u = W m is standard normal.
    float sx = px.shape.x, sy = px.shape.y, rho = px.shape.z, c = sqrt(1.0 - rho * rho);
    mat2 W = mat2(1.0 / (sx * c), 0.0, -rho / (sy * c), 1.0 / sy);
    vec2 u = W * m;
    mat2 J = W;   // d(warped u) / dm
    float detT = 1.0;
    if (s.ndf != NDF_BECKMANN) {
        // GGX (ours): the dictionary's cells converge to a Gaussian, GGX's slopes are a Student-t with 2 degrees of
        // freedom of the same scale. The radial map T(u) = u g(|u|) / |u|, g(r)^2 = 2 ln(1 + r^2 / 2), matches their
        // radial CDFs (1 - exp(-g^2 / 2) = 1 - 1 / (1 + r^2 / 2)), so Gaussian(T(u)) |dT/du| is the Student-t: the
        // expected cell NDF is GGX at every level and the cells converge to GGX with the density. |dT/du| =
        // 1 / (1 + r^2 / 2); the lobes widen in GGX's long tail.
        float r2 = dot(u, u);
        float q = 1.0 + 0.5 * r2;
        float scale = r2 > 1e-8 ? sqrt(2.0 * log(q) / r2) : 1.0;   // g(r) / r
        float slope = 1.0 / (scale * q);                           // g'(r)
        vec2 dir = r2 > 1e-8 ? u * inversesqrt(r2) : vec2(1.0, 0.0);
        mat2 dT = scale * mat2(1.0) + (slope - scale) * outerProduct(dir, dir);
        J = dT * W;
        u *= scale;
        detT = 1.0 / q;
    }
    sl.u = u;
    sl.jacobian = CHERMAIN_SIGMA_DICT * CHERMAIN_SIGMA_DICT * abs(determinant(W)) * detT;
    sl.filtered = P_ANTI_ALIASING > 0.5;
    sl.dudx = vec2(0.0);
    sl.dudy = vec2(0.0);
    if (sl.filtered) {
        vec3 dhx, dhy;
        chermainHalfVectorDerivatives(s, h, wi, wo, dhx, dhy);
        vec2 mdx, mdy;
        if (P_ANTI_ALIASING < 1.5) {   // ggaa: hemispherical derivatives; ggaa_slope: of the slope
            // Hemispherical derivatives (authors' default): of the projected half vector h.xy, used as slopes'.
            mdx = dhx.xy;
            mdy = dhy.xy;
        } else {
            // Slope derivatives: of m = -h.xy / h.z.
            mdx = -(dhx.xy * h.z - h.xy * dhx.z) / cos2;
            mdy = -(dhy.xy * h.z - h.xy * dhy.z) / cos2;
        }
        float k = P_KERNEL_SIZE / CHERMAIN_RANGE;   // kernel size, in the dictionary's texture coordinates
        sl.dudx = k * (J * mdx);
        sl.dudy = k * (J * mdy);
    }
    // Alg. 1 line 8: the two levels, blended.
    float P = 0.0;
    if (px.blend < 1.0) P += (1.0 - px.blend) * chermainLevelP22(px, px.levels[0], sl);
    if (px.blend > 0.0) P += px.blend * chermainLevelP22(px, px.levels[1], sl);
    // Eq. 6 (Alg. 1 line 10).
    return max(P, 0.0) / cos4;
}

// The roughness the environment is lit with (GLINT_ENVIRONMENT_ALPHA, shaders/glints/README.md). The authors light
// the environment with the prefiltered map at the LEAN-filtered roughness (2021 code: lod from max(sigma_x,
// sigma_y)), without glints: with normal_filtering, alpha = sqrt 2 max(sigma_x, sigma_y); else the material's.
#define GLINT_ENVIRONMENT_ALPHA 1
float glintEnvironmentAlpha(GlintPixel px, GlintSurface s) {
    return P_NORMAL_FILTERING > 0.5 ? 1.41421356 * max(px.shape.x, px.shape.y) : s.alpha;
}

// x: anisotropy after the max_anisotropy clamp, y: LOD l, z: log4 of the microfacets per cell of the finer level,
// w: the weight of the coarser level.
vec4 glintFootprintAOV(GlintPixel px, GlintSurface s) { return px.footprint; }

// x: cells evaluated per glintD call, y: cells in total, z: glintD calls, w: 1 when the pixel is smooth (no
// footprint or every cell beyond the dictionary).
vec4 glintExtraAOV(GlintPixel px, GlintSurface s) {
    float perCall = g_chermainLightCalls > 0 ? float(g_chermainCells) / float(g_chermainLightCalls) : 0.0;
    bool allSmooth = px.noFootprint || (px.levels[0].allSmooth && px.levels[1].allSmooth);
    return vec4(perCall, float(g_chermainCells), float(g_chermainLightCalls), allSmooth ? 1.0 : 0.0);
}
