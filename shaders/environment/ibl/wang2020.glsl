// IBL mode `wang2020`: Wang, Deng & Holzschuch 2020, glints under environment lighting from the prefiltered 4D
// glint table (Sec. 4.2; built by glints/wang2020/wang2020_prefilter.comp, engine/glints/wang2020/wang2020_prefilter.h) combined
// with the particle count of the pixel footprint from the glint method's per-pixel traversal (Sec. 4.3):
//   micro: L = L^o / (a(A) sigma(Omega_o) N P^) * sum_k H(lambda_k - P^)     (Eq. 20)
//   meso:  L = L^o / (a(A) sigma(Omega_o) N) * (particles in A)              (Eq. 18)
//   macro: L = L^o / sigma(Omega_o)                                          (Eq. 18 with the count N a(A))
// Needs the glint method wang2020 (its GlintPixel; the mode table enforces it); on non-glinty materials it is the
// split-sum baseline (environment/prefiltered_lookup.glsl). Diffuse: the SH irradiance (Sec. 5 "Other materials": a prefiltered map).
// Deviation: F by Schlick at n.o on the filtered radiance (the table has no F, see the prefilter's header).
// Deterministic: one evaluation, sampleIndex unused (the prefilter already integrated the environment).
#include "common/bindings.glsl"
#include "glints/wang2020/wang2020_table.glsl"

// Entry 0: the resolution (NTn, NPn, NTo, NPo); entries 1..: the table (layout in glints/wang2020/wang2020_prefilter.comp).
layout(std430, binding = BINDING_IBL_FIRST) readonly buffer WangGlintTable { vec4 u_wangGlintTable[]; };

vec4 wangTableEntry(int tn, int pn, int to, int po) {
    ivec4 n = ivec4(u_wangGlintTable[0] + 0.5);
    pn = (pn % n.y + n.y) % n.y;
    po = (po % n.w + n.w) % n.w;
    return u_wangGlintTable[1 + ((tn * n.y + pn) * n.z + to) * n.w + po];
}

// Quadrilinear lookup of (L^o, P^) for world normal nWorld and world direction toward the eye.
vec4 wangGlintTable(vec3 nWorld, vec3 toEye) {
    ivec4 size = ivec4(u_wangGlintTable[0] + 0.5);
    float thetaN = acos(clamp(nWorld.y, -1.0, 1.0));
    float phiN = atan(nWorld.z, nWorld.x);
    if (phiN < 0.0) phiN += 2.0 * PI;
    mat3 frame = wang2020Frame(thetaN, phiN);
    vec3 o = transpose(frame) * toEye;
    float thetaO = acos(clamp(o.z, 0.0, 1.0));
    float phiO = atan(o.y, o.x);
    if (phiO < 0.0) phiO += 2.0 * PI;
    float fn = thetaN / PI * float(size.x - 1), fp = phiN / (2.0 * PI) * float(size.y);
    float fo = clamp(thetaO / (0.5 * PI) * float(size.z) - 0.5, 0.0, float(size.z - 1));
    float fq = phiO / (2.0 * PI) * float(size.w);
    int tn0 = min(int(fn), size.x - 2), pn0 = int(floor(fp)), to0 = min(int(fo), max(size.z - 2, 0)), po0 = int(floor(fq));
    float wn = fn - float(tn0), wp = fp - float(pn0), wo = fo - float(to0), wq = fq - float(po0);
    vec4 sum = vec4(0.0);
    for (int c = 0; c < 16; ++c) {
        int a = c & 1, b = (c >> 1) & 1, d = (c >> 2) & 1, e = (c >> 3) & 1;
        float w = (a == 1 ? wn : 1.0 - wn) * (b == 1 ? wp : 1.0 - wp) * (d == 1 ? wo : 1.0 - wo) * (e == 1 ? wq : 1.0 - wq);
        if (w > 0.0) sum += w * wangTableEntry(tn0 + a, pn0 + b, min(to0 + d, size.z - 1), po0 + e);
    }
    return sum;
}

// Directional occlusion (Sec. 4.4): visibility (0 or 1) of the environment along the mirror direction r of the view
// about the normal, one ray as in the paper. In this rasterizer: a screen-space march in the depth buffer (16 steps,
// geometrically spaced from 2 cm to 8 m; a step is blocked when the stored surface is nearer to the camera than
// the ray point by less than 0.5 m, the assumed thickness, read at the ray point's exact screen position:
// wangDepthAt). Off-screen or behind the camera: visible.
// The 0/1 result goes to the alpha of the environment-glint target; the post pass blurs it with the paper's
// 9-tap Gaussian into the soft-shadow weight delta (shaders/glints/wang2020/wang2020_glint_occlusion_blur.frag).
layout(binding = UNIT_GBUFFER_DEPTH) uniform sampler2D u_wangDepth;   // the lighting pass's depth (reversed Z), unit 5

// The stored depth at an exact screen position (pixels), interpolated between the four nearest texels. Reversed-Z
// depth (near / view z) is affine across the image of a plane, so this is exact on flat surfaces; the nearest
// texel's depth (its centre's) lies up to half a pixel footprint in front of or behind the ray point, which at
// grazing views exceeds the 1 cm bias below: the far rows of plane25 occluded their own reflection and went black
// under the sky. Where a texel is background (an edge) the nearest texel is used.
float wangDepthAt(vec2 pixelPosition) {
    // In the outer half pixel the weights leave [0, 1]: linear extrapolation from the last two texels, also exact.
    vec2 f = pixelPosition - 0.5;
    ivec2 last = ivec2(u_viewport.xy) - 1;
    ivec2 i0 = clamp(ivec2(floor(f)), ivec2(0), max(last - 1, ivec2(0)));
    vec2 w = f - vec2(i0);
    float d00 = texelFetch(u_wangDepth, i0, 0).r;
    float d10 = texelFetch(u_wangDepth, min(i0 + ivec2(1, 0), last), 0).r;
    float d01 = texelFetch(u_wangDepth, min(i0 + ivec2(0, 1), last), 0).r;
    float d11 = texelFetch(u_wangDepth, min(i0 + ivec2(1, 1), last), 0).r;
    if (min(min(d00, d10), min(d01, d11)) <= 0.0)
        return texelFetch(u_wangDepth, clamp(ivec2(pixelPosition), ivec2(0), last), 0).r;
    return mix(mix(d00, d10, w.x), mix(d01, d11, w.x), w.y);
}

float wangDirectionalOcclusion(vec3 position, vec3 n, vec3 toEye) {
    vec3 dir = reflect(-toEye, n);
    vec3 start = position + n * 0.005;
    float t = 0.02;
    for (int i = 0; i < 16; ++i, t *= 1.55) {
        vec3 p = start + dir * t;
        vec4 clip = u_viewProjection * vec4(p, 1.0);
        if (clip.w <= 1e-4) return 1.0;
        vec3 ndc = clip.xyz / clip.w;
        if (any(greaterThan(abs(ndc.xy), vec2(1.0)))) return 1.0;
        float stored = wangDepthAt((ndc.xy * 0.5 + 0.5) * vec2(u_viewport.xy));
        if (stored <= 0.0) continue;                                 // background: nothing there
        vec4 q = u_inverseViewProjection * vec4(ndc.xy, stored, 1.0);
        float surfaceDistance = distance(q.xyz / q.w, u_cameraPosition.xyz);
        float rayDistance = distance(p, u_cameraPosition.xyz);
        if (surfaceDistance < rayDistance - 0.01 && surfaceDistance > rayDistance - 0.5) return 0.0;
    }
    return 1.0;
}

vec3 iblRadiance(GlintPixel glint, GlintSurface s, vec3 wo, vec3 toEyeWorld, mat3 worldToShading,
                 vec3 diffuseAlbedo, vec3 f0, bool glinty, uint sampleIndex) {
#ifdef GLINT_METHOD_WANG2020
    if (glinty && glint.expected > 0.0 && wo.z > 0.0) {
        vec4 table = wangGlintTable(s.n, toEyeWorld);
        float sigmaO = 2.0 * PI * (1.0 - cos(PS_GAMMA * PI / 180.0));   // the shared table's gamma
        float filteredP = clamp(table.a, 1e-8, 1.0);
        // Eq. 20 (micro), Eq. 18 (meso), macro, with the transition bands of the glint method: all three are
        // (reflecting count) / (a(A) sigma N P^) with the count for acceptance probability P^.
        float factor = wangReflectingCount(glint, filteredP) / (glint.expected * sigmaO * filteredP);
        vec3 F = F_Schlick(f0, clamp(wo.z, 0.0, 1.0));
        // To the method's lighting targets (glints/wang2020/wang2020.glsl, which the lighting pass of wang2020 always
        // has): the glint before occlusion and the visibility; the blurred visibility multiplies it there (Sec. 4.4).
        g_postEnvironmentGlint = wangGlintColor() * F * max(table.rgb, vec3(0.0)) * factor;
        g_postVisibility = wangDirectionalOcclusion(s.position, s.n, toEyeWorld);
        return envDiffuse(s.n) * diffuseAlbedo;
    }
#endif
    // Non-glinty pixels: the split sum with local reflections. The glint table above is prefiltered from the
    // distant map only (a per-probe table is not built).
    return envLightingAt(s.position, s.n, toEyeWorld, diffuseAlbedo, f0, s.alpha, s.ndf);
}
