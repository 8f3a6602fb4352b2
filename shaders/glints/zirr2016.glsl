// Baseline: Zirr & Kaplanyan 2016, "Real-time rendering of procedural multiscale materials" (I3D 2016), as
// described by Deliot & Belcour 2023 Sec. 3 (Eq. 7) and Sec. 6.3 (Eq. 15). Interface: shaders/glints/README.md.
//  - Random seeds live on axis-aligned mip grids on the surface (square texels of side 2^lod in UV).
//  - Each texel holds N = density x texel area facets; its count of reflecting facets is a binomial draw
//    b(N, p) with p = R D(h) / D(n) (the same counting NDF as Deliot & Belcour Eq. 4, so the two methods differ
//    only in how they cover footprints and blend levels).
//  - Anisotropic footprints are covered by stepping along the major axis over up to 16 texels (the usual cap):
//    beyond ratio 16 the texel size grows isotropically (the stretched-glint artifact, D&B Fig. 11).
//  - Levels of detail blend by lerping the normalized binomial outputs (D&B Eq. 7; the ghosting of Fig. 2, 10).
//  - Binomial: Gaussian approximation when N p > 5, otherwise a sum of Bernoulli trials (up to 16; D&B Eq. 15).
// Angular lifespan: the same bilinear hemispherical grid as our Deliot & Belcour implementation (cell of
// projected area R / D(n)), so both methods' glints live equally long in angle (our choice for a fair comparison).
// Deviation for N > 16 with N p <= 5: 16 trials of probability N p / 16 (keeps the mean; ZK16 clamps the trials).

const int ZIRR_MAX_ANISOTROPY = 16;
const int ZIRR_MAX_TRIALS = 16;

struct GlintPixel {
    vec2 firstSample;      // UV of the first sample along the major axis
    vec2 sampleStep;       // UV step between samples
    int samples;           // texels covered along the major axis, 1..16
    int lod0;              // lower mip level; the upper is lod0 + 1
    float lodT;            // lerp weight of the upper level (fract of the continuous LOD)
    float facetsLo;        // facets per texel at lod0 (density x 4^lod0 x density scale)
    float Dn;              // D(n)
    float angularCellSize; // projected-h cell of the angular grid
    float footprintFacets; // density x footprint-equivalent area, for --aov extra
    vec4 footprint;        // anisotropy ratio, LOD, samples, clamped (1 when ratio > 16)
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

// D&B Eq. 15: floor of a Gaussian N(Np, Np(1-p)) when N p > 5, else the sum of Bernoulli trials.
float zirrBinomial(float N, float p, uvec3 seed) {
    if (!(N > 0.0) || !(p > 0.0)) return 0.0;
    p = min(p, 1.0);
    float mean = N * p;
    if (mean > 5.0) {
        uvec3 r = zirrHash3(seed);
        float g = sqrt(-2.0 * log(zirrUnit(r.x))) * cos(2.0 * PI * zirrUnit(r.y));
        return clamp(floor(mean + sqrt(mean * (1.0 - p)) * g), 0.0, N);
    }
    bool few = N <= float(ZIRR_MAX_TRIALS);
    int trials = few ? int(ceil(N)) : ZIRR_MAX_TRIALS;
    float pTrial = few ? p : mean / float(ZIRR_MAX_TRIALS);
    float count = 0.0;
    uvec3 state = seed;
    for (int i = 0; i < trials; ++i) {
        state = zirrHash3(state + uvec3(uint(i), 0u, 0u));
        float q = few ? pTrial * min(1.0, N - float(i)) : pTrial;   // the last trial of a fractional N is partial
        count += zirrUnit(state.x) < q ? 1.0 : 0.0;
    }
    return count;
}

GlintPixel glintSetup(GlintSurface s) {
    GlintPixel px;
    FootprintEllipse e = footprintEllipse(s.duvdx, s.duvdy);
    float major = max(e.major, 1e-20);
    float minor = max(e.minor, major * 1e-6);
    float ratio = major / minor;
    px.samples = clamp(int(ceil(ratio)), 1, ZIRR_MAX_ANISOTROPY);
    // Beyond the cap the texels grow isotropically until 16 of them cover the major axis.
    float coveredMinor = max(minor, major / float(ZIRR_MAX_ANISOTROPY));
    float lod = clamp(log2(coveredMinor * P_SCREEN_SPACE_SCALE), -100.0, 100.0);
    px.lod0 = int(floor(lod));
    px.lodT = lod - floor(lod);
    float density = exp(clamp(P_LOG_DENSITY, 0.0, 50.0)) * max(s.densityScale, 0.0);
    px.facetsLo = density * exp2(2.0 * float(px.lod0));
    px.sampleStep = e.majorDir * (2.0 * major / float(px.samples));
    px.firstSample = s.uv - e.majorDir * major + 0.5 * px.sampleStep;
    px.Dn = D_smooth(vec3(0.0, 0.0, 1.0), s.alpha, s.ndf);
    px.angularCellSize = sqrt(P_MICROFACET_ROUGHNESS / max(px.Dn, 1e-20));
    px.footprintFacets = density * exp2(2.0 * lod) * float(px.samples);
    px.footprint = vec4(ratio, lod, float(px.samples), ratio > float(ZIRR_MAX_ANISOTROPY) ? 1.0 : 0.0);
    return px;
}

float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    g_zirrLightCalls += 1;
    float R = P_MICROFACET_ROUGHNESS;
    float p = clamp(R * D_smooth(h, s.alpha, s.ndf) / max(px.Dn, 1e-30), 0.0, 1.0);
    vec2 q = h.xy / px.angularCellSize - 0.5;
    vec2 qBase = floor(q);
    vec2 f = q - qBase;
    ivec2 a0 = ivec2(qBase);
    float angularWeight[4] = float[4]((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    float level[2] = float[2](0.0, 0.0);
    for (int l = 0; l < 2; ++l) {
        int lod = px.lod0 + l;
        float facets = px.facetsLo * (l == 0 ? 1.0 : 4.0);
        float invSize = exp2(-float(lod));
        for (int j = 0; j < px.samples; ++j) {
            ivec2 texel = ivec2(floor((px.firstSample + float(j) * px.sampleStep) * invSize));
            for (int a = 0; a < 4; ++a) {
                ivec2 cell = a0 + ivec2(a & 1, a >> 1);
                uvec3 seed = uvec3(uint(texel.x), uint(texel.y),
                                   zirrHash3(uvec3(uint(lod + 4096), uint(cell.x), uint(cell.y))).x);
                level[l] += angularWeight[a] * zirrBinomial(facets, p, seed);
            }
            g_zirrEvaluations += 4;
        }
        level[l] /= max(facets * float(px.samples), 1e-30);
    }
    // D&B Eq. 7: lerp of the two levels' normalized counts (ZK16's blend), then Eq. 4's D(n)/R.
    return px.facetsLo > 0.0 ? px.Dn / R * mix(level[0], level[1], px.lodT) : 0.0;
}

vec4 glintFootprintAOV(GlintPixel px, GlintSurface s) { return px.footprint; }

// x: binomial evaluations per glintD call (2 levels x samples x 4 angular cells: varies with the footprint),
// y: total, z: glintD calls, w: 1 / facets in the footprint (density x texel area x samples).
vec4 glintExtraAOV(GlintPixel px, GlintSurface s) {
    float perCall = g_zirrLightCalls > 0 ? float(g_zirrEvaluations) / float(g_zirrLightCalls) : 0.0;
    return vec4(perCall, float(g_zirrEvaluations), float(g_zirrLightCalls),
                px.footprintFacets > 0.0 ? 1.0 / px.footprintFacets : 0.0);
}
