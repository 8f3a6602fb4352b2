// Kemppinen, Paulin, Thonat, Thiery, Lehtinen, Boubekeur 2025, "Evaluating and Sampling Glinty NDFs in
// Constant Time" (ACM TOG 44(6)): the parts shared by evaluation (kemppinen2025.glsl) and importance sampling
// (kemppinen2025_sampling.glsl): the NDF-to-prior mappings T (Sec. 3.2.1-3.2.2), the smooth NDF they invert,
// the implicit 4D jittered grid (Sec. 3.3.1) and the Gaussian / erf helpers. No dependence on the lighting pass,
// so a compute shader can include it. CPU twin: engine/reference/kemppinen2025_reference.cpp (keep in step).

// ---- Prior space U: the disk of radius 1/2 inscribed in the unit square (Sec. 3.2, "a disk inscribed in the
// unit square"). Every mapping below first produces a point p of the unit disk, then x = 0.5 + 0.5 p.

// Anisotropic GGX (Walter et al. 2007 / Atanasov et al. 2022 form): D = 1 / (pi ax ay |M^T h|^4) with
// M^T h = (hx/ax, hy/ay, hz). With ax = ay it is common/brdf.glsl's D_GGX.
float kemppinenGgxD(vec3 h, vec2 alpha) {
    if (h.z <= 0.0) return 0.0;
    vec3 v = vec3(h.xy / alpha, h.z);
    float l2 = dot(v, v);
    return 1.0 / (PI * alpha.x * alpha.y * l2 * l2);
}

// Anisotropic Beckmann: exp(-(mx^2/ax^2 + my^2/ay^2)) / (pi ax ay cos^4), m the slope h.xy / h.z.
float kemppinenBeckmannD(vec3 h, vec2 alpha) {
    if (h.z <= 0.0) return 0.0;
    vec2 s = h.xy / (h.z * alpha);
    float cos2 = h.z * h.z;
    return exp(-dot(s, s)) / (PI * alpha.x * alpha.y * cos2 * cos2);
}

float kemppinenSmoothD(vec3 h, vec2 alpha, int ndf) {
    return ndf == NDF_BECKMANN ? kemppinenBeckmannD(h, alpha) : kemppinenGgxD(h, alpha);
}

// Sec. 3.2.1, Eq. 6-7: T = L o M~ for GGX. M~ (the microsurface transformation of Atanasov et al.) maps the GGX
// of roughness (ax, ay) to the uniform NDF, |J_M~| = |M| / |M^T h|^4 = pi D(h); Lambert's equal-area projection
// L(x, y, z) = (x, y) / sqrt(1 + z) maps the uniform hemisphere onto the unit disk. Note: Eq. 6's |J| is the
// NDF's transformation rule; as a solid-angle Jacobian M~ has |M| / |M^T h|^3, so T's Jacobian is
// pi D |M^T h| / 8 rather than proportional to D (tested). The expectation of D*^f is D pointwise all the same,
// because Eq. 5 weights every lobe by D(h) itself (Eq. 3 tip).
vec2 kemppinenGgxToDisk(vec3 h, vec2 alpha) {
    vec3 w = normalize(vec3(h.xy / alpha, max(h.z, 0.0)));
    return w.xy / sqrt(1.0 + w.z);
}

vec3 kemppinenDiskToGgx(vec2 p, vec2 alpha) {
    // Inverse of L: z = 1 - r^2, (x, y) = p sqrt(2 - r^2); then the inverse stretch of M~.
    float r2 = min(dot(p, p), 1.0);
    vec3 w = vec3(p * sqrt(2.0 - r2), 1.0 - r2);
    return normalize(vec3(w.xy * alpha, w.z));
}

// Sec. 3.2.2: T = B1^-1 o B2^-1 for Beckmann. B2^-1 takes h to its slope h.xy / h.z; B1^-1 (Marsaglia's polar
// map read backwards) takes the Gaussian slope s (in units of alpha) to the disk point s/|s| sqrt(1 - exp(-|s|^2)).
vec2 kemppinenBeckmannToDisk(vec3 h, vec2 alpha) {
    vec2 s = h.xy / (max(h.z, 1e-7) * alpha);
    float s2 = dot(s, s);
    // (1 - exp(-s2)) / s2, written to stay accurate near the pole (no expm1 in GLSL).
    float ratio = s2 < 1e-4 ? 1.0 - 0.5 * s2 : (1.0 - exp(-s2)) / s2;
    return s * sqrt(ratio);
}

vec3 kemppinenDiskToBeckmann(vec2 p, vec2 alpha) {
    float r2 = min(dot(p, p), 1.0 - 1e-7);
    // B1: |s|^2 = -log(1 - r^2); ratio = |s|^2 / r^2, accurate near the pole.
    float ratio = r2 < 1e-4 ? 1.0 + 0.5 * r2 : -log(1.0 - r2) / r2;
    vec2 slope = p * sqrt(ratio) * alpha;
    return normalize(vec3(slope, 1.0));   // B2
}

// T: shading-frame half vector -> prior space [0,1]^2 (the disk of radius 1/2 centred at (1/2, 1/2)).
vec2 kemppinenToPrior(vec3 h, vec2 alpha, int ndf) {
    vec2 p = ndf == NDF_BECKMANN ? kemppinenBeckmannToDisk(h, alpha) : kemppinenGgxToDisk(h, alpha);
    return 0.5 + 0.5 * p;
}

// T^-1: prior space -> shading-frame half vector.
vec3 kemppinenFromPrior(vec2 x, vec2 alpha, int ndf) {
    vec2 p = 2.0 * x - 1.0;
    return ndf == NDF_BECKMANN ? kemppinenDiskToBeckmann(p, alpha) : kemppinenDiskToGgx(p, alpha);
}

// ---- Sec. 3.3.1: the implicit 4D jittered grid. Cell (spatial i, j; angular a, b) at level l of process q holds
// one point; its jitter, roulette number and colour come from a counter-based hash of the cell (a PCG-style 4D
// hash: "a congruential RNG as they are fast to seed"). Negative cell indices are converted int -> uint (bit
// pattern), never float -> uint (undefined for negative values).
uvec4 kemppinenHash4(uvec4 v) {
    v = v * 1664525u + 1013904223u;
    v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
    v ^= v >> 16u;
    v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
    return v;
}

struct KemppinenPoint {
    vec2 spatial;    // jitter in [0,1)^2 inside the spatial cell
    vec2 angular;    // jitter in [0,1)^2 inside the angular cell
    float roulette;  // r of Eq. 8
    float hue;       // colour variable (Sec. 3.3.6)
};

KemppinenPoint kemppinenPoint(ivec2 spatialCell, ivec2 angularCell, int level, int process) {
    uvec4 key = uvec4(uint(spatialCell.x), uint(spatialCell.y), uint(angularCell.x), uint(angularCell.y));
    key ^= uvec4(uint(level) * 0x9E3779B9u, uint(process) * 0x85EBCA6Bu, uint(level) * 0xC2B2AE35u,
                 uint(process + 1) * 0x27D4EB2Fu);
    uvec4 h = kemppinenHash4(key);
    const float inv16 = 1.0 / 65536.0;
    KemppinenPoint p;
    // High halves for the 4D position (the best-mixed bits), low halves for roulette and colour.
    p.spatial = vec2(h.xy >> 16u) * inv16;
    p.angular = vec2(h.zw >> 16u) * inv16;
    p.roulette = float(h.x & 0xFFFFu) * inv16;
    p.hue = float(h.y & 0xFFFFu) * inv16;
    return p;
}

// Per-glint colour (Sec. 3.3.6): 1 + v cos(2 pi (hue + channel/3)). The mean over the uniform hue is exactly 1 in
// each channel, so the compensation term (which must use the mean colour) stays white and energy is unchanged.
vec3 kemppinenGlintColor(float hue, float variation) {
    return 1.0 + variation * cos(2.0 * PI * (hue + vec3(0.0, 1.0 / 3.0, 2.0 / 3.0)));
}

// Eq. 8: mollified Russian roulette, eps = 0.1 as in the paper.
float kemppinenRoulette(float r, float w) {
    const float eps = 0.1;
    return smoothstep(max(0.0, r - eps), min(1.0, r + eps), w);
}

// erf by Abramowitz & Stegun 7.1.26 (|error| < 1.5e-7): the "simple rational polynomial approximation" of
// Sec. 3.3.4. Odd extension for negative arguments.
float kemppinenErf(float x) {
    float a = abs(x);
    float t = 1.0 / (1.0 + 0.3275911 * a);
    float poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
    float y = 1.0 - poly * exp(-a * a);
    return x < 0.0 ? -y : y;
}

// Mass of the 1D Gaussian N(x, sigma) over [lo, hi] (0 when empty).
float kemppinenIntervalMass(float x, float sigma, float lo, float hi) {
    if (hi <= lo) return 0.0;
    float s = 1.0 / (sqrt(2.0) * sigma);
    return 0.5 * (kemppinenErf((hi - x) * s) - kemppinenErf((lo - x) * s));
}
