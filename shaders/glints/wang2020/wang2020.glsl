// Wang, Deng & Holzschuch 2020, "Real-time glints rendering with prefiltered discrete stochastic microfacets":
// the three-scale glint pass (Sec. 4.3) for point and directional lights through the DPF (Sec. 5, Eq. 21).
// Data (engine/glints/wang2020/wang2020_resources.cpp): the DPF P(i, o, gamma) accumulated for each material's roughness
// and NDF at the shared gamma (Sec. 4.4; 3D texture: x = phi_o - phi_i in [0, 180] deg, y = theta_o, z = theta_i in [0, 90) deg)
// and the particle quadtree (counts per node, level by level; engine/glints/wang2020/wang2020_quadtree.h). Particle
// positions and lambda come from the same integer hashes as the CPU reference.
//
// The pixel footprint A is the parallelogram uv + s duv/dx + t duv/dy, |s|, |t| <= 1/2 (area a(A) = |det J|).
// Expected particle count in A: E = N a(A). Scale (Sec. 4.3): E < P_MICRO_MAX micro, E > P_MACRO_MIN macro, meso
// between. Counts of reflecting particles:
//   micro: sum over particles in A of H(lambda_k - P) (Eq. 7-8, Eq. 20 with P(i, o, gamma) for lights, Sec. 5),
//   meso:  (particles in A) x P (Eq. 18, no per-particle test),
//   macro: E x P (no traversal).
// Deviation (parameter `transition`, octaves of E; 0 = the paper's hard switch): in the band
// [P_MICRO_MAX, P_MICRO_MAX 2^w) a meso pixel also traverses as micro and blends the two counts linearly in log E
// (micro weight 1 at the threshold, 0 at the band's end); in (P_MACRO_MIN 2^-w, P_MACRO_MIN] it blends meso into
// macro the same way. Both counts have the same expectation, so the mean is unchanged; the blend replaces the
// abrupt change of texture at the thresholds (sparse glints -> uniform sheen) by a gradual one.
// Eq. 3 with Eq. 4: f = (i.h) F D^ G / (a(A) sigma(Omega_o) (i.n)(o.n)), D^ = count / N. lighting.frag computes
// D G F / (4 (i.n)(o.n)), so glintD returns D_eq = 4 (i.h) D^ / (a(A) sigma(Omega_o) (h.n)). The 1 / (h.n) is ours:
// particle normals follow D(m)(m.n) (projected area), so this makes E[D_eq] = D(h) of the particles' NDF (the material's: GGX or Beckmann) as the interface asks.
// Deviations: the paper's tree nodes store id, count, depth, child count and AABB (two float4); ours is an
// implicit complete tree of one word per node (wang2020::shaderNodeWords): a node holding a single particle names
// that particle's leaf (micro pixels test it at once, meso pixels descend only its path), an inner node its count
// and its non-empty children (only those are pushed). The traversal gathers once per pixel in glintSetup (the
// paper's two-step traversal with a tree cut, Sec. 5), so lights only compare lambdas.
// Extended lights (README "Extended lights"): Sec. 5 shades point and directional lights with the DPF of their
// direction; an area light's glints are that at its centre direction over the smooth NDF there (the lighting pass's
// fallback). Its environment glints (Sec. 4) are the IBL mode `wang2020`, the default when this method is selected.
#include "common/bindings.glsl"

// Glint colour (Sec. 4.5): an RGB tint of the glints, through the RGB-NDF path of lighting.frag.
#define GLINT_COLOR_D 1

layout(binding = UNIT_METHOD_FIRST) uniform sampler3D u_wangDpf;
layout(std430, binding = BINDING_METHOD_FIRST) readonly buffer WangQuadtree { uint u_wangNodes[]; };
// One accumulated DPF per distinct (NDF, roughness) of the glinty materials, stacked along z (slot k holds theta_i
// rows [k T, (k + 1) T)), and each material's slot; slot 0 is the shared values' table (u_wangDpf).
layout(binding = UNIT_METHOD_FIRST + 1) uniform sampler3D u_wangDpfStack;
layout(std430, binding = BINDING_METHOD_FIRST + 1) readonly buffer WangMaterialSlots {
    uvec4 u_wangStack;   // slot count, theta_i rows per slot
    uint u_wangMaterialSlot[];
};

#define WANG_MAX_LAMBDAS 16
#define WANG_STACK 48
#define WANG_MAX_VISITS 1024
#define WANG_SCALE_MICRO 0
#define WANG_SCALE_MESO 1
#define WANG_SCALE_MACRO 2

struct GlintPixel {
    int scale;
    float expected;        // N a(A)
    float area;            // a(A)
    float inFootprint;     // particles found in A (micro, meso)
    int lambdaCount;       // micro: lambdas stored
    float microWeight;     // meso pixels in the micro/meso band: weight of the micro count (else 0)
    float macroWeight;     // meso pixels in the meso/macro band: weight of the macro count (else 0)
    float lambdas[WANG_MAX_LAMBDAS];
    int visits;            // nodes visited (cost, --aov extra)
};

// Lighting targets (shaders/glints/README.md; the table entry lists two, so the lighting program is compiled with
// GLINT_METHOD_TARGETS): the light loop and the wang2020 IBL mode put the glint radiance here instead of into the
// radiance; the method's passes blur the occlusion, multiply, blur the glints and add them (Sec. 4.4,
// shaders/glints/wang2020/wang2020_glint_*.frag). The IBL mode sets the environment glint (before occlusion) and its
// visibility along the mirror direction.
#if defined(GLIMMER_LIGHTING_PASS) && defined(GLINT_METHOD_TARGETS)
vec3 g_postEnvironmentGlint = vec3(0.0);
float g_postVisibility = 1.0;
vec3 g_wangLightGlints = vec3(0.0);
layout(location = 2) out vec4 o_glintEnvironment;  // rgb: environment glints, a: visibility (glinty pixels)
layout(location = 3) out vec4 o_glintLights;       // rgb: light glints, a: 1 on glinty pixels (occlusion-blur mask)

bool glintTakeLightGlint(vec3 radiance) {
    g_wangLightGlints += radiance;
    return true;
}
void glintScaleTargets(float share) {
    g_wangLightGlints *= share;
    g_postEnvironmentGlint *= share;
}
void glintWriteTargets(bool glinty, bool finalView) {
    bool postGlints = finalView && glinty;
    o_glintEnvironment = postGlints ? vec4(finiteOrZero(g_postEnvironmentGlint), clamp(g_postVisibility, 0.0, 1.0))
                                    : vec4(0.0);
    o_glintLights = postGlints ? vec4(finiteOrZero(g_wangLightGlints), 1.0) : vec4(0.0);
}
#endif

// PCG output permutation; identical to wang2020::pcgHash (engine/glints/wang2020/wang2020_quadtree.h).
uint wangHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
float wangHashUnit(uint leafId, uint particle, uint channel) {
    uint h = wangHash(wangHash(leafId) + particle * 8u + channel);
    return float(h >> 8u) * (1.0 / 16777216.0);
}

// The node words of wang2020::shaderNodeWords: WANG_SINGLE_PARTICLE | the leaf of the node's one particle (x in bits
// 0-12, y in 13-25, relative to the node); WANG_CHILD_MASK | its non-empty children (bits 26-29) | its count
// (bits 0-25); or its plain count (leaves, and inner nodes whose four children all hold particles).
#define WANG_SINGLE_PARTICLE 0x80000000u
#define WANG_CHILD_MASK 0x40000000u

uint wangNodeWord(int level, ivec2 cell) {
    int mask = (1 << level) - 1;
    uint offset = ((1u << uint(2 * level)) - 1u) / 3u;
    return u_wangNodes[offset + (uint(cell.y & mask) << uint(level)) + uint(cell.x & mask)];
}

// Footprint-local coordinates (s, t) of a UV point; inside when both are within [-1/2, 1/2].
vec2 wangLocal(vec2 p, vec2 center, mat2 inverseJ) { return inverseJ * (p - center); }
bool wangInside(vec2 st) { return abs(st.x) <= 0.5 && abs(st.y) <= 0.5; }

GlintPixel glintSetup(GlintSurface s) {
    GlintPixel px;
    px.lambdaCount = 0;
    px.inFootprint = 0.0;
    px.visits = 0;
    px.microWeight = 0.0;
    px.macroWeight = 0.0;
    for (int i = 0; i < WANG_MAX_LAMBDAS; ++i) px.lambdas[i] = 1.0;
    float det = s.duvdx.x * s.duvdy.y - s.duvdx.y * s.duvdy.x;
    px.area = abs(det);
    // Per-material density (this material's N over the tree's N, x material scale x glint mask, clamped to 1):
    // independent thinning of the tree's particles (particle k kept when its hash channel 5 is below the keep
    // fraction), so N x scale particles per unit UV square without a per-material tree. The tree is built for the
    // densest glinty material (PS_PARTICLES, GlintMethod::sharedDataMaterial); keep 1 is the CPU reference's case.
    float keep = clamp(s.densityScale * P_PARTICLES / max(PS_PARTICLES, 1e-30), 0.0, 1.0);
    px.expected = PS_PARTICLES * keep * px.area;
    px.scale = px.expected < P_MICRO_MAX ? WANG_SCALE_MICRO
             : (px.expected > P_MACRO_MIN ? WANG_SCALE_MACRO : WANG_SCALE_MESO);
    if (px.scale == WANG_SCALE_MESO && P_TRANSITION > 0.0) {
        px.microWeight = clamp(1.0 - log2(px.expected / P_MICRO_MAX) / P_TRANSITION, 0.0, 1.0);
        px.macroWeight = clamp(1.0 - log2(P_MACRO_MIN / px.expected) / P_TRANSITION, 0.0, 1.0);
    }
#ifdef GLIMMER_LIGHTING_PASS
    // lighting.frag sets up every pixel; glints (and the traversal) only on glinty materials. Scale -1: none.
    if (u_materials[s.materialId].alphaMetallicNdfGlinty.w < 0.5) {
        px.scale = -1;
        px.expected = 0.0;
        return px;
    }
#endif
    if (px.scale == WANG_SCALE_MACRO || px.area < 1e-20 || s.densityScale <= 0.0) return px;

    // Spatial traversal (Sec. 4.3 micro / meso): from the level whose cells are at least the footprint's AABB
    // (at most 2 x 2 of them overlap it), descend into non-empty nodes overlapping the AABB. Meso adds nodes
    // wholly inside A without descending (no per-particle test is needed there).
    mat2 inverseJ = inverse(mat2(s.duvdx, s.duvdy));
    vec2 halfExtent = 0.5 * (abs(s.duvdx) + abs(s.duvdy));
    vec2 lo = s.uv - halfExtent, hi = s.uv + halfExtent;
    int depth = int(PS_DEPTH + 0.5);   // the shared tree's depth
    float extent = max(2.0 * max(halfExtent.x, halfExtent.y), 1e-30);
    int startLevel = clamp(int(floor(-log2(extent))), 0, depth);
    float cells = exp2(float(startLevel));
    ivec2 c0 = ivec2(floor(lo * cells)), c1 = ivec2(floor(hi * cells));
    // A stack entry is one uint: levels below startLevel (bits 28-31) and the cell relative to c0 at that level (x in
    // bits 0-13, y in 14-27; below 3 x 2^12 for depth <= 12). llvmpipe keeps a local array in memory and reads it
    // per pixel: one word per entry instead of an ivec3 was 0.83x of wang2020's lighting pass on the court.
    uint stack[WANG_STACK];
    int top = 0;
    for (int y = 0; y <= c1.y - c0.y && y <= 2; ++y)
        for (int x = 0; x <= c1.x - c0.x && x <= 2; ++x) stack[top++] = uint(y << 14 | x);
    // Meso pixels skip the per-particle work, except in the micro/meso band (they need the lambdas too).
    bool meso = px.scale == WANG_SCALE_MESO && px.microWeight <= 0.0;
    float leafSize = exp2(-float(depth));
    while (top > 0 && px.visits < WANG_MAX_VISITS) {
        uint entry = stack[--top];
        int below = int(entry >> 28u);
        ivec2 cell = (c0 << below) + ivec2(int(entry & 0x3FFFu), int((entry >> 14u) & 0x3FFFu));
        ivec3 node = ivec3(startLevel + below, cell);
        ++px.visits;
        uint word = wangNodeWord(node.x, node.yz);
        if (word == 0u) continue;
        // A single particle: its leaf (unwrapped, like the node's cell). Micro pixels test the particle itself:
        // the node tests below could only cull what the particle test rejects.
        bool single = word >= WANG_SINGLE_PARTICLE;
        bool masked = !single && word >= WANG_CHILD_MASK;
        uint count = single ? 1u : (masked ? word & 0x03FFFFFFu : word);
        uint children = masked ? (word >> 26u) & 0xFu : 0xFu;
        ivec2 leaf = single ? (node.yz << (depth - node.x)) + ivec2(int(word & 0x1FFFu), int((word >> 13u) & 0x1FFFu))
                            : node.yz;
        if (!single || meso) {
            float size = exp2(-float(node.x));
            vec2 nodeLo = vec2(node.yz) * size, nodeHi = nodeLo + size;
            if (any(greaterThan(nodeLo, hi)) || any(lessThan(nodeHi, lo))) continue;
            // Separating axes of the parallelogram (its s and t axes; the AABB test above covers the box's axes):
            // nodes beside a thin, slanted footprint are culled, not descended.
            vec2 q0 = wangLocal(nodeLo, s.uv, inverseJ), q1 = wangLocal(nodeHi, s.uv, inverseJ);
            vec2 q2 = wangLocal(vec2(nodeLo.x, nodeHi.y), s.uv, inverseJ), q3 = wangLocal(vec2(nodeHi.x, nodeLo.y), s.uv, inverseJ);
            vec2 qMin = min(min(q0, q1), min(q2, q3)), qMax = max(max(q0, q1), max(q2, q3));
            if (any(greaterThan(qMin, vec2(0.5))) || any(lessThan(qMax, vec2(-0.5)))) continue;
            if (meso && all(lessThanEqual(abs(qMin), vec2(0.5))) && all(lessThanEqual(abs(qMax), vec2(0.5)))) {
                px.inFootprint += float(count) * keep;   // node wholly inside A (thinning in expectation)
                continue;
            }
            if (node.x < depth) {
                // Descend: into the child on the single particle's path (its siblings are empty), else all four.
                uint rel = entry & 0x0FFFFFFFu;
                uint childBase = uint(below + 1) << 28u | (rel << 1u & 0x0FFFC000u) | (rel << 1u & 0x3FFEu);
                if (single) {
                    ivec2 r = (leaf >> (depth - node.x - 1)) & 1;
                    stack[top++] = childBase | uint(r.y << 14 | r.x);
                    continue;
                }
                if (top + 4 > WANG_STACK) continue;  // cannot happen for depth <= 12 (3 siblings per level + 4)
                for (int c = 0; c < 4; ++c)
                    if ((children & (1u << uint(c))) != 0u) stack[top++] = childBase | uint((c >> 1) << 14 | (c & 1));
                continue;
            }
        }
        {
            int mask = (1 << depth) - 1;
            uint leafId = (uint(leaf.y & mask) << uint(depth)) | uint(leaf.x & mask);
            for (uint k = 0u; k < count; ++k) {
                vec2 p = (vec2(leaf) + vec2(wangHashUnit(leafId, k, 0u), wangHashUnit(leafId, k, 1u))) * leafSize;
                if (!wangInside(wangLocal(p, s.uv, inverseJ))) continue;
                if (keep < 1.0 && wangHashUnit(leafId, k, 5u) >= keep) continue;
                px.inFootprint += 1.0;
                if (!meso && px.lambdaCount < WANG_MAX_LAMBDAS) px.lambdas[px.lambdaCount++] = wangHashUnit(leafId, k, 2u);
            }
        }
    }
    return px;
}

// P(i, o, gamma) from the accumulated table (Sec. 5: lights use P directly, no prefiltering).
float wangDpf(vec3 wi, vec3 wo) {
    float thetaI = acos(clamp(wi.z, -1.0, 1.0)), thetaO = acos(clamp(wo.z, -1.0, 1.0));
    float phi = abs(atan(wo.y, wo.x) - atan(wi.y, wi.x));
    if (phi > PI) phi = 2.0 * PI - phi;
    // The table of this pixel's material (g_glintMaterial, lighting.frag; -1 outside it: the shared table).
    uint slot = g_glintMaterial >= 0 && uint(g_glintMaterial) < uint(u_wangMaterialSlot.length())
                    ? min(u_wangMaterialSlot[g_glintMaterial], u_wangStack.x - 1u) : 0u;
    float rows = float(u_wangStack.y);
    float z = clamp(thetaI / (0.5 * PI) * rows, 0.5, rows - 0.5) + float(slot) * rows;   // no blend across slots
    return texture(u_wangDpfStack, vec3(phi / PI, thetaO / (0.5 * PI), z / (rows * float(u_wangStack.x)))).r;
}

// Particles of the footprint that reflect, for acceptance probability P (P(i, o, gamma) for lights, the filtered
// P^ for the environment), by the pixel's scale (Sec. 4.3) and, in the transition bands, blended (header).
float wangReflectingCount(GlintPixel px, float P) {
    // micro, Eq. 20 / Eq. 7-8: particle k reflects when lambda_k < P (H(lambda - P) = 1 for lambda - P < 0).
    // Particles beyond the stored lambdas (more than WANG_MAX_LAMBDAS, only when the count far exceeds its
    // expectation) count with probability P.
    float micro = 0.0;
    for (int k = 0; k < px.lambdaCount; ++k) micro += px.lambdas[k] < P ? 1.0 : 0.0;
    micro += (px.inFootprint - float(px.lambdaCount)) * P;
    float meso = px.inFootprint * P;   // Eq. 18
    float macro = px.expected * P;     // area x density x DPF
    if (px.scale == WANG_SCALE_MICRO) return micro;
    if (px.scale == WANG_SCALE_MACRO) return macro;
    return mix(mix(meso, micro, px.microWeight), macro, px.macroWeight);
}

float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    if (px.expected <= 0.0 || h.z <= 1e-4 || s.densityScale <= 0.0) return 0.0;
    float P = min(wangDpf(wi, wo), 1.0);
    float reflecting = wangReflectingCount(px, P);
    float sigmaO = 2.0 * PI * (1.0 - cos(PS_GAMMA * PI / 180.0));   // the shared table's gamma
    float D = 4.0 * max(dot(wi, h), 0.0) * reflecting / (px.expected * sigmaO * h.z);
    return isnan(D) || isinf(D) ? 0.0 : D;
}

vec3 wangGlintColor() { return vec3(P_COLOR_R, P_COLOR_G, P_COLOR_B); }

vec3 glintColorD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    return wangGlintColor() * glintD(px, s, h, wi, wo);
}

// --aov footprint: x expected particle count N a(A), y scale (0 micro, 1 meso, 2 macro), z particles found, w nodes
// visited.
vec4 glintFootprintAOV(GlintPixel px, GlintSurface s) {
    return vec4(px.expected, float(px.scale), px.inFootprint, float(px.visits));
}

// --aov extra (and --aov glintscale): the scale as a colour, red micro, green meso, blue macro (Fig. 4a), mixed
// by the blend weights in the transition bands; black on materials without glints.
vec4 glintExtraAOV(GlintPixel px, GlintSurface s) {
    if (px.scale == WANG_SCALE_MICRO) return vec4(1.0, 0.0, 0.0, 1.0);
    if (px.scale == WANG_SCALE_MACRO) return vec4(0.0, 0.0, 1.0, 1.0);
    if (px.scale != WANG_SCALE_MESO) return vec4(0.0, 0.0, 0.0, 1.0);
    float micro = px.microWeight, macro = px.macroWeight;
    return vec4(micro, (1.0 - micro) * (1.0 - macro), macro, 1.0);
}
