// Linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt 2016, "Real-Time Polygonal-Light Shading with Linearly
// Transformed Cosines", ACM TOG 35(4)): a lobe over light directions is approximated by a clamped cosine mapped by a
// 3 x 3 matrix M (Eq. 1-3); its integral over a light is the clamped cosine's integral over the light mapped by M^-1
// (Eq. 7), which has closed forms:
// - polygons (rect lights): clip to the upper hemisphere, then Lambert's edge sum (Sec. 3.3, Eq. 11; Appendix);
// - ellipses (disk lights, and spheres as the disk of their silhouette): the cone through the mapped ellipse has an
//   exact vector form factor from its principal axes; clipped by the horizon as the sphere cap of the same form factor
//   (Heitz & Hill 2017, "Real-Time Line- and Disk-Light Shading", SIGGRAPH course; the cap formula is Snyder 1996's).
// M^-1, the lobe magnitudes and the NDF-only lobe of Kneiphof & Klein 2024 come from the tables fitted at build time
// (tools/ltc_fit; layout in engine/render/lights/ltc_tables.h). The CPU mirror of every function here is
// engine/reference/area_light_reference.cpp (tests compare both with brute-force quadrature).
#include "common/bindings.glsl"
#include "common/constants.glsl"

layout(binding = UNIT_LTC_TABLE) uniform sampler2DArray u_ltcTable;
const float LTC_TABLE_SIZE = 32.0;   // engine/render/lights/ltc_tables.h kTableSize
const int LTC_LAYER_SPECULAR = 0;    // + ndf
const int LTC_LAYER_NDF_ONLY = 2;    // + ndf
const int LTC_LAYER_MAGNITUDE = 4;   // + ndf

// What the light loop needs of the tables at one pixel (looked up once, shared by every area light).
struct LtcPixel {
    mat3 toFrame;        // world -> (t1 towards the view in the tangent plane, t2, n)
    mat3 invSpecular;    // M^-1 of the specular lobe (BRDF x cosine)
    mat3 invNdfOnly;     // M^-1 of D(h) / (4 |v.h|) (Kneiphof & Klein 2024's dedicated LTC)
    vec2 splitSum;       // (A, B): the specular lobe integrates to f0 A + B (Schlick)
    float ndfOnly;       // the integral of D(h) / (4 |v.h|) over the hemisphere of lights
};

// A loop bound the compiler cannot fold (u_viewport.x, the frame's width, is never negative; common/frame.glsl): the
// clipping and edge loops below stay loops instead of being unrolled at every call site, which made llvmpipe's
// compile of the lighting program seconds longer. Such loops are written do-while where they run at least once:
// llvmpipe runs a loop's body under its execution mask, and a loop tested at its top cost one more pass through the
// body (with every pixel masked off) than the same loop tested at its bottom (issue 39: the lighting pass 0.86x on
// the atrium's court in five interleaved pairs, lighting.frag's light loops and the two below).
int ltcLoopCount(int n) { return u_viewport.x >= 0 ? n : 0; }

// M^-1 from a table entry (a, b, c, d) = [[a, 0, b], [0, 1, 0], [c, 0, d]] (GLSL matrices are column-major).
mat3 ltcInverse(vec4 e) { return mat3(vec3(e.x, 0.0, e.z), vec3(0.0, 1.0, 0.0), vec3(e.y, 0.0, e.w)); }

LtcPixel ltcSetup(vec3 n, vec3 toEye, float alpha, int ndf) {
    LtcPixel px;
    float cosTheta = clamp(dot(n, toEye), 0.0, 1.0);
    vec3 t1 = toEye - n * dot(n, toEye);
    float len = length(t1);
    t1 = len > 1e-6 ? t1 / len : (abs(n.x) < 0.9 ? normalize(cross(n, vec3(1.0, 0.0, 0.0))) : normalize(cross(n, vec3(0.0, 1.0, 0.0))));
    vec3 t2 = cross(n, t1);
    px.toFrame = transpose(mat3(t1, t2, n));
    // Row = sqrt(alpha), column = sqrt(1 - cos theta), texel centres at the ends.
    vec2 uv = (vec2(sqrt(1.0 - cosTheta), sqrt(clamp(alpha, 0.0, 1.0))) * (LTC_TABLE_SIZE - 1.0) + 0.5) / LTC_TABLE_SIZE;
    px.invSpecular = ltcInverse(texture(u_ltcTable, vec3(uv, float(LTC_LAYER_SPECULAR + ndf))));
    px.invNdfOnly = ltcInverse(texture(u_ltcTable, vec3(uv, float(LTC_LAYER_NDF_ONLY + ndf))));
    vec4 magnitude = texture(u_ltcTable, vec3(uv, float(LTC_LAYER_MAGNITUDE + ndf)));
    px.splitSum = magnitude.xy;
    px.ndfOnly = magnitude.z;
    return px;
}

// The integral of D(h) / (4 |v.h|) over the hemisphere of lights (Kneiphof & Klein 2024's NDF-only pre-integrated
// term; the environment glints' p_base times the total NDF).
float ltcNdfOnlyIntegral(float alpha, float cosTheta, int ndf) {
    vec2 uv = (vec2(sqrt(1.0 - clamp(cosTheta, 0.0, 1.0)), sqrt(clamp(alpha, 0.0, 1.0))) * (LTC_TABLE_SIZE - 1.0) + 0.5) / LTC_TABLE_SIZE;
    return texture(u_ltcTable, vec3(uv, float(LTC_LAYER_MAGNITUDE + ndf))).z;
}

// acos(x) / sqrt(1 - x^2) (= theta / sin theta for x = cos theta), with its series near x = 1 where float acos loses
// its digits.
float ltcThetaOverSin(float x) {
    float y = 1.0 - x;
    if (y < 1e-4) return 1.0 + y * (1.0 / 3.0);
    return acos(clamp(x, -1.0, 1.0)) * inversesqrt(max(1.0 - x * x, 1e-12));
}

// (1 / pi) x the integral of max(0, l.z) over the directions through the quad q (relative to the shaded point):
// clipped to z >= 0 (at most 5 vertices), then Lambert's sum of theta_i (n . unit normal of edge i) / (2 pi).
float ltcQuadCosine(vec3 q0, vec3 q1, vec3 q2, vec3 q3) {
    vec3 q[4] = vec3[4](q0, q1, q2, q3);
    vec3 c[6];
    int n = 0;
    int e = 0;
    do {
        vec3 a = q[e], b = q[(e + 1) & 3];
        if (a.z >= 0.0 && n < 6) c[n++] = a;
        if ((a.z >= 0.0) != (b.z >= 0.0) && n < 6) c[n++] = a + (a.z / (a.z - b.z)) * (b - a);
        ++e;
    } while (e < ltcLoopCount(4));
    if (n < 3) return 0.0;
    float sum = 0.0;
    int i = 0;
    do {
        vec3 a = normalize(c[i]), b = normalize(c[i + 1 < n ? i + 1 : 0]);
        sum += ltcThetaOverSin(dot(a, b)) * cross(a, b).z;
        ++i;
    } while (i < min(n, ltcLoopCount(6)));
    return abs(sum) * (0.5 * INV_PI);
}

// (1 / pi) x the integral of max(0, l.z) over a spherical cap with sin^2(half-angle) = s whose axis has z = c (the
// cap clipped by the horizon; exact).
float ltcCapCosine(float s, float c) {
    s = clamp(s, 0.0, 1.0);
    c = clamp(c, -1.0, 1.0);
    if (s <= 0.0) return 0.0;
    if (c * c >= s) return c > 0.0 ? s * c : 0.0;
    float sinElevation = sqrt(max(1.0 - c * c, 0.0));
    float x = sqrt(max(1.0 / s - 1.0, 0.0));   // cot(half-angle)
    float y = sinElevation > 0.0 ? clamp(-x * c / sinElevation, -1.0, 1.0) : 0.0;
    float w = sinElevation * sqrt(max(1.0 - y * y, 0.0));
    float result = (c * acos(y) - x * w) * s + (x > 0.0 ? atan(w / x) : 0.5 * PI);
    return max(result * INV_PI, 0.0);
}

// Smallest eigenvalue of a symmetric 3 x 3 matrix (trigonometric solution of the characteristic cubic; Smith 1961).
float ltcSmallestEigenvalue(mat3 a) {
    float p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    float q = (a[0][0] + a[1][1] + a[2][2]) * (1.0 / 3.0);
    float p2 = (a[0][0] - q) * (a[0][0] - q) + (a[1][1] - q) * (a[1][1] - q) + (a[2][2] - q) * (a[2][2] - q) + 2.0 * p1;
    float p = sqrt(p2 * (1.0 / 6.0));
    if (p <= 1e-30) return q;
    float r = clamp(determinant((a - mat3(q)) * (1.0 / p)) * 0.5, -1.0, 1.0);
    return q + 2.0 * p * cos(acos(r) * (1.0 / 3.0) + 2.0943951);
}

// Vector form factor of the elliptic cone through an ellipse (centre C, conjugate semi-axes U, V; relative to the
// point): its magnitude `formFactor` and unit axis. The cone x^T Q x <= 0 with Q = (U U^T + V V^T - C C^T)^-1;
// with mu_i the eigenvalues of Q^-1 (mu3 < 0 < mu1, mu2), the cone's cross-section at unit distance along its axis
// has semi-axes sqrt(-mu_i / mu3), whose cone has form factor sqrt(mu1 mu2 / ((mu1 - mu3)(mu2 - mu3))). mu1 mu2 =
// det(U V C)^2 / -mu3 and mu1 + mu2 = trace - mu3 avoid the two small eigenvalues, which lose their digits in float
// for small lights (mu3 ~ -d^2 and mu1, mu2 ~ r^2). False when the ellipse is seen edge-on.
bool ltcEllipseFormFactor(vec3 C, vec3 U, vec3 V, out float formFactor, out vec3 axis) {
    float scale = 1.0 / max(length(C), 1e-20);   // a uniform scale changes no direction
    C *= scale;
    U *= scale;
    V *= scale;
    formFactor = 0.0;
    axis = vec3(0.0, 0.0, 1.0);
    float detB = determinant(mat3(U, V, C));
    if (!(abs(detB) > 1e-9)) return false;
    mat3 m = outerProduct(U, U) + outerProduct(V, V) - outerProduct(C, C);
    float mu3 = ltcSmallestEigenvalue(m);
    if (!(mu3 < 0.0)) return false;
    float mu12 = detB * detB / -mu3;
    float sum12 = dot(U, U) + dot(V, V) - dot(C, C) - mu3;
    float denominator = mu12 - mu3 * sum12 + mu3 * mu3;
    formFactor = sqrt(clamp(mu12 / max(denominator, 1e-30), 0.0, 1.0));
    // Axis: the null vector of m - mu3 I, the largest cross product of two of its rows.
    mat3 k = m - mat3(mu3);
    vec3 r0 = vec3(k[0][0], k[1][0], k[2][0]), r1 = vec3(k[0][1], k[1][1], k[2][1]), r2 = vec3(k[0][2], k[1][2], k[2][2]);
    vec3 c01 = cross(r0, r1), c02 = cross(r0, r2), c12 = cross(r1, r2);
    float d01 = dot(c01, c01), d02 = dot(c02, c02), d12 = dot(c12, c12);
    vec3 best = d01 >= d02 && d01 >= d12 ? c01 : (d02 >= d12 ? c02 : c12);
    float len = length(best);
    if (!(len > 0.0)) return false;
    axis = best / len;
    if (dot(axis, C) < 0.0) axis = -axis;
    return true;
}

// (1 / pi) x the integral of max(0, l.z) over the cone through an ellipse.
float ltcEllipseCosine(vec3 C, vec3 U, vec3 V) {
    float formFactor;
    vec3 axis;
    if (!ltcEllipseFormFactor(C, U, V, formFactor, axis)) return 0.0;
    return ltcCapCosine(formFactor, axis.z);
}
