// Octahedral unit-vector code (Meyer et al. 2010, "On Floating-Point Normal Vectors"; Cigolle et al. 2014, Sec. 3.1):
// a unit vector in two numbers in [-1, 1], for the G-buffer's clear coat normal (two half floats).
#ifndef GLIMMER_OCTAHEDRAL_GLSL
#define GLIMMER_OCTAHEDRAL_GLSL

vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

vec2 octahedralEncode(vec3 n) {
    vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    return n.z < 0.0 ? (1.0 - abs(p.yx)) * signNotZero(p) : p;
}

vec3 octahedralDecode(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signNotZero(n.xy);
    return normalize(n);
}

#endif
