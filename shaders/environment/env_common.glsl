// Shared by the environment precompute passes: cube texel directions (GL face conventions, OpenGL 4.5 Table 8.19;
// CPU mirror: envref::cubeTexelDirection), the equirectangular mapping (envref::directionToEquirect), a
// Hammersley point set, and NDF importance sampling of half vectors.
#include "common/brdf.glsl"

// Direction through point `texel` (in texel units, centre = +0.5) of face `face` of a size x size cube.
vec3 cubeDirection(int face, vec2 texel, int size) {
    vec2 st = 2.0 * texel / float(size) - 1.0;
    float s = st.x, t = st.y;
    vec3 d;
    if (face == 0) d = vec3(1.0, -t, -s);
    else if (face == 1) d = vec3(-1.0, -t, s);
    else if (face == 2) d = vec3(s, 1.0, t);
    else if (face == 3) d = vec3(s, -1.0, -t);
    else if (face == 4) d = vec3(s, -t, 1.0);
    else d = vec3(-s, -t, -1.0);
    return normalize(d);
}

// u = 0.5 at -z growing towards +x, v = 0 at +y (rows top-down, as uploaded).
vec2 equirectUv(vec3 d) {
    return vec2(atan(d.x, -d.z) * (0.5 * INV_PI) + 0.5, acos(clamp(d.y, -1.0, 1.0)) * INV_PI);
}

vec2 hammersley(uint i, uint count) {
    return vec2((float(i) + 0.5) / float(count), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}

// Half vector in the frame z = normal, distributed with density D(h) cos(theta_h).
// GGX: tan^2 = alpha^2 xi / (1 - xi) (Walter et al. 2007, Eq. 35); Beckmann: tan^2 = -alpha^2 ln(1 - xi) (Eq. 28).
vec3 sampleHalfVector(vec2 xi, float alpha, int ndf) {
    float a2 = alpha * alpha;
    float tan2 = ndf == NDF_BECKMANN ? -a2 * log(max(1.0 - xi.x, 1e-12)) : a2 * xi.x / max(1.0 - xi.x, 1e-12);
    float cosTheta = inversesqrt(1.0 + tan2);
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    float phi = 2.0 * PI * xi.y;
    return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// An orthonormal frame around n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
mat3 frameAround(vec3 n) {
    float sgn = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + n.z);
    float b = n.x * n.y * a;
    vec3 t = vec3(1.0 + sgn * n.x * n.x * a, sgn * b, -sgn * n.x);
    vec3 bt = vec3(b, sgn + n.y * n.y * a, -n.y);
    return mat3(t, bt, n);
}
