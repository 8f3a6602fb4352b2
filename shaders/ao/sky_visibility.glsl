// Lookup of the baked sky visibility (engine/render/ao/sky_visibility.h, which mirrors it in C++ as
// SkyVisibilityGrid::evaluate): probe grid of (a, b) with V(w) ~ a + b.w, invalid probes a < 0. The point moves half
// a cell along its normal; the 8 probes around it weigh trilinearly times a wrap factor that favours probes in
// front of the surface; the cosine-weighted visibility of the normal's hemisphere is a + (2/3) b.n.
layout(binding = UNIT_AO_SKY) uniform sampler3D u_skyProbes;   // RGBA32F, texelFetch only
layout(location = 8) uniform vec4 u_skyOrigin;                 // xyz grid origin, w cell size
layout(location = 9) uniform ivec4 u_skyDims;                  // xyz probe counts, w: 1 when baked

float skyVisibility(vec3 position, vec3 normal) {
    if (u_skyDims.w == 0) return 1.0;
    float cell = u_skyOrigin.w;
    vec3 g = (position + normal * (0.5 * cell) - u_skyOrigin.xyz) / cell - 0.5;
    vec3 base = floor(g), f = g - base;
    vec4 sum = vec4(0.0);
    float weightSum = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 offset = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        ivec3 i = clamp(ivec3(base) + offset, ivec3(0), u_skyDims.xyz - 1);
        vec4 probe = texelFetch(u_skyProbes, i, 0);
        if (probe.x < 0.0) continue;
        vec3 t = mix(1.0 - f, f, vec3(offset));
        vec3 toProbe = u_skyOrigin.xyz + (vec3(i) + 0.5) * cell - position;
        float len = length(toProbe);
        float facing = len > 1e-6 ? 0.5 * (dot(toProbe / len, normal) + 1.0) : 1.0;
        float w = t.x * t.y * t.z * (facing * facing + 0.2);
        sum += w * probe;
        weightSum += w;
    }
    if (weightSum < 1e-5) return 1.0;
    sum /= weightSum;
    return clamp(sum.x + (2.0 / 3.0) * dot(sum.yzw, normal), 0.0, 1.0);
}
