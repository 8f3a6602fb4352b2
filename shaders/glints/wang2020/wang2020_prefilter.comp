// Wang et al. 2020, Sec. 4.2 / 4.4 "Environment Map Prefiltering": for every sampled (normal n, view direction o)
// the filtered glint radiance (Eq. 16, K = 64 importance samples of the Beckmann NDF) and the filtered DPF (Eq. 17,
// B = 36 x 9 uniform hemisphere samples), one vec4 (rgb L^o, a P^) per entry of the 4D table.
// Table layout (engine/glints/wang2020/wang2020_prefilter.h): entry 0 the resolution, then index ((tn * NPn + pn) * NTo + to) * NPo + po;
// theta_n = tn / (NTn - 1) * pi, phi_n = pn / NPn * 2 pi (world, y up); o in the frame of n (wang2020Frame):
// theta_o = (to + 0.5) / NTo * pi / 2, phi_o = po / NPo * 2 pi.
// Estimators of Eq. 16 (u_estimator, IBL parameter ibl.prefilter):
//   0 "dpf" (default), the paper's form: m_j ~ D(m)(m.n), i_j = reflect(o, m_j), weight L P(i_j, o, gamma) M / pdf(i_j).
//   1 "cone" (ours, optional): the same integral with P written as the reflection density integrated over the
//     gamma-cone (P(i, o) = int_cone p(o'|i) do', which is how our DPF tables are built): o'_j uniform in the cone,
//     m_j ~ D(m)(m.n), i_j = reflect(o'_j, m_j); p(o'|i) / pdf(i|o') = 4 (o'.m) / (4 (i.m)) = 1, so each sample weighs
//     sigma L(i_j) M(i_j, o). At grazing view angles the literal form's 64 samples came out 14-49 % low (theta_o 76.5-85.5,
//     alpha 0.1, constant map: the cone-blurred P and the unblurred NDF samples disagree, a heavy tail); the cone
//     form stays within 1 % of the quadrature there up to 76.5 degrees (tests/wang2020_test.cpp). Under maps with tiny
//     very bright lamps neither 64-sample estimate is reliable and the cone form measured lower on the top view of
//     the studio map (0.57-0.69 of the expectation against 0.96-0.97), so the paper's form stays the default.
//     engine/glints/wang2020_reference.cpp has both on the CPU.
// Deviations: F is left out of M (Eq. 11) and applied at run time with Schlick at n.o, because F0 is a per-pixel
// base colour here (the paper prefilters per material). M carries 1 / (h.n) instead of 1 / (i.n) with the cosine
// of the rendering equation folded in (the same normalization as the light path, see glints/wang2020.glsl).
#include "common/bindings.glsl"
layout(local_size_x = 64) in;
#include "common/constants.glsl"
#include "common/brdf.glsl"
#include "environment/prefiltered_lookup.glsl"
#include "glints/wang2020/wang2020_table.glsl"

layout(binding = UNIT_METHOD_FIRST) uniform sampler3D u_wangDpf;
layout(std430, binding = BINDING_IBL_FIRST) writeonly buffer WangPrefiltered { vec4 u_wangTableOut[]; };
uniform ivec4 u_tableSize;   // NTn, NPn, NTo, NPo
uniform float u_alpha;
uniform float u_gamma;       // search cone half-angle, radians
uniform int u_estimator;     // 0 dpf (the paper's form), 1 cone (ours)

float wangDpfLookup(vec3 wi, vec3 wo) {
    float thetaI = acos(clamp(wi.z, -1.0, 1.0)), thetaO = acos(clamp(wo.z, -1.0, 1.0));
    float phi = abs(atan(wo.y, wo.x) - atan(wi.y, wi.x));
    if (phi > PI) phi = 2.0 * PI - phi;
    return min(texture(u_wangDpf, vec3(phi / PI, thetaO / (0.5 * PI), thetaI / (0.5 * PI))).r, 1.0);
}

float radicalInverse(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10;
}

void main() {
    uint index = gl_GlobalInvocationID.x;
    uint total = uint(u_tableSize.x * u_tableSize.y * u_tableSize.z * u_tableSize.w);
    if (index >= total) return;
    int po = int(index % uint(u_tableSize.w));
    int to = int((index / uint(u_tableSize.w)) % uint(u_tableSize.z));
    int pn = int((index / uint(u_tableSize.w * u_tableSize.z)) % uint(u_tableSize.y));
    int tn = int(index / uint(u_tableSize.w * u_tableSize.z * u_tableSize.y));
    float thetaN = float(tn) / float(max(u_tableSize.x - 1, 1)) * PI;
    float phiN = float(pn) / float(u_tableSize.y) * 2.0 * PI;
    mat3 frame = wang2020Frame(thetaN, phiN);   // columns: x, y, n (world)
    float thetaO = (float(to) + 0.5) / float(u_tableSize.z) * 0.5 * PI;
    float phiO = float(po) / float(u_tableSize.w) * 2.0 * PI;
    vec3 wo = vec3(sin(thetaO) * cos(phiO), sin(thetaO) * sin(phiO), cos(thetaO));

    // Eq. 16: L^o(n, o) = sum_j L_i(i_j) P(i_j, o, gamma) M(i_j, o) / (pdf(i_j) K), i_j = reflect(o, m_j) with
    // m_j ~ D(m)(m.n) (Hammersley points), pdf(i) = D(m)(m.n) / (4 |o.m|); or its cone form (header).
    const uint K = 64u;
    vec3 radiance = vec3(0.0);
    float a2 = u_alpha * u_alpha;
    float cosGamma = cos(u_gamma), sigma = 2.0 * PI * (1.0 - cosGamma);
    vec3 coneX = normalize(cross(abs(wo.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0), wo));
    vec3 coneY = cross(wo, coneX);
    for (uint j = 0u; j < K; ++j) {
        float u1 = (float(j) + 0.5) / float(K), u2 = radicalInverse(j);
        float tan2 = -a2 * log(1.0 - u1);
        float cosM = inversesqrt(1.0 + tan2), sinM = sqrt(max(1.0 - cosM * cosM, 0.0));
        vec3 m = vec3(sinM * cos(2.0 * PI * u2), sinM * sin(2.0 * PI * u2), cosM);
        vec3 toward = wo;   // the direction the particle reflects into: o, or o' in the cone
        if (u_estimator == 1) {
            // R2 sequence (plastic-number additive recurrence) for o', uniform in solid angle over the cone.
            float v1 = fract(0.5 + float(j) * 0.75487766), v2 = fract(0.5 + float(j) * 0.56984029);
            float cosT = 1.0 - v1 * (1.0 - cosGamma), sinT = sqrt(max(1.0 - cosT * cosT, 0.0));
            toward = normalize(sinT * cos(2.0 * PI * v2) * coneX + sinT * sin(2.0 * PI * v2) * coneY + cosT * wo);
            if (toward.z <= 0.0) continue;   // below the horizon: the DPF records no reflection there
        }
        float om = dot(toward, m);
        if (om <= 0.0) continue;
        vec3 wi = 2.0 * om * m - toward;
        if (wi.z <= 0.0) continue;
        float G = G1_Beckmann(wi, u_alpha) * G1_Beckmann(wo, u_alpha);
        vec3 h = u_estimator == 1 ? normalize(wi + wo) : m;   // M(i, o) takes the half vector of i and o
        float M = dot(wi, h) * G / (h.z * wo.z);            // Eq. 11 without F, 1/(h.n) (see header)
        float weight;
        if (u_estimator == 1) {
            weight = sigma * M;
        } else {
            float P = wangDpfLookup(wi, wo);
            float pdf = D_Beckmann(m, u_alpha) * m.z / (4.0 * om);
            weight = P * M / max(pdf, 1e-12);
        }
        radiance += envRadiance(frame * wi, 0.0) * weight;
    }
    radiance /= float(K);

    // Eq. 17: P^(n, o) = sum_j 2 pi P(i_j, o, gamma) / B over B = 36 x 9 directions uniform in solid angle.
    float filtered = 0.0;
    for (int k = 0; k < 9; ++k)
        for (int l = 0; l < 36; ++l) {
            float cosI = 1.0 - (float(k) + 0.5) / 9.0, sinI = sqrt(1.0 - cosI * cosI);
            float phiI = (float(l) + 0.5) / 36.0 * 2.0 * PI;
            filtered += wangDpfLookup(vec3(sinI * cos(phiI), sinI * sin(phiI), cosI), wo);
        }
    filtered *= 2.0 * PI / (36.0 * 9.0);
    u_wangTableOut[index + 1u] = vec4(radiance, filtered);   // entry 0: the resolution (written by the CPU)
}
