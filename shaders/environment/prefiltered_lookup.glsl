// Image-based lighting lookups for the lighting pass (maps built by engine/environment/environment.cpp).
// Specular: split-sum approximation (Karis 2013, "Real Shading in Unreal Engine 4", Eq. 2-4): prefiltered radiance
// at the mirror direction (mip chosen by roughness, layer by NDF) times the BRDF table's f0 * A + B.
// Diffuse: irradiance from order-2 spherical harmonics (Ramamoorthi & Hanrahan 2001, Eq. 13), weighted by
// (1 - f0 * A - B) so the Lambertian base receives what the specular layer does not reflect (a white dielectric
// then reflects exactly the incident constant radiance: the white furnace holds). The per-light loop of
// lighting.frag keeps its unweighted Lambert + Cook-Torrance sum.
// Deviation: glinty materials get the smooth prefiltered baseline here; glint methods act on the lights only.
// Local reflections: the *At lookups (envLightingAt, envPrefilteredAt, envRadianceAt) read the reflection probe
// whose influence box holds the shaded point (render/probes/reflection_probes.h), parallax-corrected to its proxy box
// (Lagarde & Zanuttini 2012), and blend it with the distant map by the probe's coverage alpha. Diffuse stays the
// distant SH irradiance (probes hold no irradiance).
#include "common/bindings.glsl"
#include "common/constants.glsl"

layout(binding = UNIT_ENV_SPECULAR) uniform samplerCubeArray u_envSpecular;   // layer = NDF; one level: the unfiltered map
layout(binding = UNIT_ENV_BRDF_LUT) uniform sampler2D u_envBrdfLut;           // (n.v, sqrt(alpha)) -> GGX (A, B), Beckmann (A, B)
layout(binding = UNIT_ENV_SOURCE) uniform samplerCube u_envSource;          // unfiltered map, box-filtered mip chain (IBL modes)
layout(binding = UNIT_ENV_SPECULAR_FINE) uniform samplerCubeArray u_envSpecularFine;   // rungs 1 .. 16 (envRung)

// Mirrors EnvironmentUniforms in engine/environment/environment.h (std140).
layout(std140, binding = BINDING_ENVIRONMENT) uniform EnvironmentBlock {
    vec4 u_envSh[9];      // rgb: irradiance / pi, cosine-convolved SH coefficients
    vec4 u_envParams;     // x intensity, y enabled, z rungs - 1, w alpha of rung 1 (envPrefiltered)
    vec4 u_envRotation;   // x cos, y sin of env.rotation about +y
};

// Mirrors ProbeUniforms in engine/render/probes/reflection_probes.h (std140). A block with count 0 is bound when the
// frame reads no probes.
struct GpuProbe {
    vec4 position;       // xyz capture point, w fade distance at the influence faces
    vec4 influenceMin;
    vec4 influenceMax;
    vec4 proxyMin;       // box the reflected ray is intersected with
    vec4 proxyMax;
};
layout(std140, binding = BINDING_PROBES) uniform ProbeBlock {
    vec4 u_probeParams;  // x count, y last prefiltered level
    GpuProbe u_probes[8];
};
// Premultiplied radiance (rgb) and coverage (a), layer = 2 * probe + NDF; level 0 unfiltered, level k holds
// sqrt(alpha) = k / 5 (a mip chain, not the environment's ladder).
layout(binding = UNIT_PROBE_SPECULAR) uniform samplerCubeArray u_probeSpecular;

bool envEnabled() { return u_envParams.y > 0.5; }

// World direction -> map direction: the map is turned by +rotation about +y (CPU: envref::worldToEnvironment).
vec3 envDirection(vec3 d) {
    float c = u_envRotation.x, s = u_envRotation.y;
    return vec3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}

// Radiance seen along world direction d (the sky behind the geometry): the unfiltered level 0.
vec3 envBackground(vec3 d) {
    return u_envParams.x * textureLod(u_envSpecular, vec4(envDirection(d), 0.0), 0.0).rgb;
}

// Radiance of the unfiltered map around world direction d at mip level `lod` (0 = full resolution; each level
// halves the face size with a 2x2 box filter). For Monte Carlo and filtered-sampling IBL modes. Under the
// procedural sky with an analytic sun light, the map holds the sky without the sun (no double counting).
vec3 envRadiance(vec3 d, float lod) {
    return u_envParams.x * textureLod(u_envSource, envDirection(d), lod).rgb;
}

// Number of mip levels of the map read by envRadiance (face size 2^(levels - 1)).
float envSourceLevels() { return float(textureQueryLevels(u_envSource)); }

// Irradiance / pi at world normal n (Ramamoorthi & Hanrahan 2001, Eq. 13 with the constants folded into u_envSh).
vec3 envDiffuse(vec3 n) {
    vec3 d = envDirection(n);
    vec3 e = u_envSh[0].rgb * 0.282095
           + u_envSh[1].rgb * (0.488603 * d.y) + u_envSh[2].rgb * (0.488603 * d.z) + u_envSh[3].rgb * (0.488603 * d.x)
           + u_envSh[4].rgb * (1.092548 * d.x * d.y) + u_envSh[5].rgb * (1.092548 * d.y * d.z)
           + u_envSh[6].rgb * (0.315392 * (3.0 * d.z * d.z - 1.0)) + u_envSh[7].rgb * (1.092548 * d.x * d.z)
           + u_envSh[8].rgb * (0.546274 * (d.x * d.x - d.y * d.y));
    return u_envParams.x * max(e, vec3(0.0));
}

// One rung of the roughness ladder (environment/environment.h, kRungs): rung 0 is the unfiltered map, rung i >= 1 holds
// alpha = alphaMin x (1 / alphaMin)^((i - 1) / (rungs - 1)), in the fine array at mip (i - 1) / 4, cube
// ndf x 4 + (i - 1) % 4.
const int ENV_RUNGS_PER_MIP = 4;   // = Environment::kSublevels (else wrong rungs: SplitSumShadingMatchesCpu fails)
vec3 envRung(vec3 direction, int rung, int ndf) {
    if (rung == 0) return textureLod(u_envSpecular, vec4(direction, float(ndf)), 0.0).rgb;
    int i = rung - 1;
    return textureLod(u_envSpecularFine, vec4(direction, float(ndf * ENV_RUNGS_PER_MIP + i % ENV_RUNGS_PER_MIP)),
                      float(i / ENV_RUNGS_PER_MIP)).rgb;
}

// Prefiltered radiance around world direction r for NDF roughness alpha, from the rungs around it. The rungs are
// 1.24x apart in alpha and are combined in log radiance, not linearly as trilinear filtering would: a small bright
// lamp that only the wider lobe reaches grows with roughness roughly as exp(-c / alpha^2) (Beckmann) or alpha^2
// (GGX tails), so a linear blend takes in far too much of it (measured: docs/measurements.md). Deviation from Karis
// 2013 (trilinear over the mip chain), for that accuracy; costs three cube fetches per pixel.
vec3 envPrefiltered(vec3 r, float alpha, int ndf) {
    float steps = u_envParams.z, alphaMin = u_envParams.w;   // rungs - 1, alpha of rung 1
    alpha = clamp(alpha, 0.0, 1.0);
    vec3 direction = envDirection(r);
    if (alpha < alphaMin) {
        // Between the mirror and rung 1: geometric blend along sqrt(alpha), as between a mip chain's levels.
        float t = sqrt(alpha / alphaMin);
        vec3 a = envRung(direction, 0, ndf), b = envRung(direction, 1, ndf);
        vec3 floorValue = 1e-4 * max(a, b) + 1e-12;
        return u_envParams.x * max(exp(mix(log(a + floorValue), log(b + floorValue), t)) - floorValue, vec3(0.0));
    }
    // Position on the ladder, linear in log alpha; a quadratic in (log alpha, log L) through the two rungs around it
    // and the next one (the one below at the top), clamped to the pair's range: a lamp's log radiance is smooth in
    // log alpha but curved, which a straight line through the pair misses (docs/measurements.md).
    float position = 1.0 + steps * log(alpha / alphaMin) / log(1.0 / alphaMin);
    float lower = clamp(floor(position), 1.0, steps);   // rung below, so lower + 1 <= rungs
    float third = lower + 2.0 <= steps + 1.0 ? lower + 2.0 : lower - 1.0;
    vec3 a = envRung(direction, int(lower), ndf);
    vec3 b = envRung(direction, int(lower) + 1, ndf);
    vec3 c = envRung(direction, int(third), ndf);
    float u = position, ua = lower, ub = lower + 1.0, uc = third;   // rung index is linear in log alpha
    float wa = (u - ub) * (u - uc) / ((ua - ub) * (ua - uc));
    float wb = (u - ua) * (u - uc) / ((ub - ua) * (ub - uc));
    float wc = (u - ua) * (u - ub) / ((uc - ua) * (uc - ub));
    vec3 floorValue = 1e-4 * max(max(a, b), c) + 1e-12;
    vec3 logL = wa * log(a + floorValue) + wb * log(b + floorValue) + wc * log(c + floorValue);
    return u_envParams.x * max(clamp(exp(logL) - floorValue, min(a, b), max(a, b)), vec3(0.0));
}

// Split-sum (A, B) for n.v and alpha.
vec2 envBrdf(float nDotV, float alpha, int ndf) {
    vec4 t = texture(u_envBrdfLut, vec2(nDotV, sqrt(clamp(alpha, 0.0, 1.0))));
    return ndf == NDF_BECKMANN ? t.ba : t.rg;
}

// Reflected radiance from the environment for a metalness-workflow surface (world-space n, unit vector to eye).
vec3 envLighting(vec3 n, vec3 toEye, vec3 diffuseAlbedo, vec3 f0, float alpha, int ndf) {
    float nDotV = clamp(dot(n, toEye), 1e-4, 1.0);
    vec3 r = reflect(-toEye, n);
    vec2 ab = envBrdf(nDotV, alpha, ndf);
    vec3 specularAlbedo = f0 * ab.x + ab.y;
    vec3 specular = envPrefiltered(r, alpha, ndf) * specularAlbedo;
    vec3 diffuse = diffuseAlbedo * (1.0 - specularAlbedo) * envDiffuse(n);
    return diffuse + specular;
}

// The probe whose influence box holds `position` (the smallest when boxes nest: an object's own probe wins over a
// larger one around it) and its weight, 1 inside and falling linearly to 0 over the fade distance at the box faces.
// Returns -1 when none does.
int probeAt(vec3 position, out float weight) {
    int best = -1;
    float bestVolume = 3.4e38;
    weight = 0.0;
    int count = int(u_probeParams.x + 0.5);
    int i = 0;
    if (count > 0) do {   // tested at the bottom: lights/ltc.glsl ltcLoopCount; `continue` goes to the test
        vec3 lo = u_probes[i].influenceMin.xyz, hi = u_probes[i].influenceMax.xyz;
        if (any(lessThan(position, lo)) || any(greaterThan(position, hi))) continue;
        vec3 extent = hi - lo;
        float volume = extent.x * extent.y * extent.z;
        if (volume >= bestVolume) continue;
        vec3 inside = min(position - lo, hi - position);
        best = i;
        bestVolume = volume;
        weight = clamp(min(inside.x, min(inside.y, inside.z)) / max(u_probes[i].position.w, 1e-4), 0.0, 1.0);
    } while (++i < count);
    return best;
}

// Parallax correction (Lagarde & Zanuttini 2012, "Local Image-based Lighting With Parallax-corrected Cubemap"):
// the ray from `position` along r leaves the proxy box at the farthest-of-nearest slab exit; the probe is read in
// the direction from its capture point to that exit point. Applied at every roughness: the paper's distortion of
// rough lobes near the box faces is accepted (no lobe-dependent blend back to r).
vec3 probeDirection(int i, vec3 position, vec3 r) {
    vec3 safe = mix(vec3(1e-6), vec3(-1e-6), lessThan(r, vec3(0.0)));
    vec3 rr = mix(r, safe, lessThan(abs(r), vec3(1e-6)));
    vec3 tMax = (u_probes[i].proxyMax.xyz - position) / rr;
    vec3 tMin = (u_probes[i].proxyMin.xyz - position) / rr;
    vec3 tExit = max(tMax, tMin);
    float t = max(min(tExit.x, min(tExit.y, tExit.z)), 0.0);
    vec3 d = position + t * r - u_probes[i].position.xyz;
    return dot(d, d) > 1e-12 ? d : r;
}

// Weighted probe lookup at `lod` for world position and direction (vec4(0): no probe, the distant map alone).
vec4 probeSample(vec3 position, vec3 r, float lod, int ndf) {
    if (u_probeParams.x < 0.5) return vec4(0.0);
    float weight;
    int i = probeAt(position, weight);
    if (i < 0 || weight <= 0.0) return vec4(0.0);
    return weight * textureLod(u_probeSpecular, vec4(probeDirection(i, position, r), float(2 * i + ndf)), lod);
}

// envPrefiltered with local reflections at `position`: probe (premultiplied) over the distant map.
vec3 envPrefilteredAt(vec3 position, vec3 r, float alpha, int ndf) {
    vec3 distant = envPrefiltered(r, alpha, ndf);
    vec4 probe = probeSample(position, r, sqrt(clamp(alpha, 0.0, 1.0)) * u_probeParams.y, ndf);
    return probe.rgb + (1.0 - probe.a) * distant;
}

// envRadiance(d, 0) (unfiltered level 0) with local reflections at `position`, for the Monte Carlo modes.
vec3 envRadianceAt(vec3 position, vec3 d) {
    vec3 distant = envRadiance(d, 0.0);
    vec4 probe = probeSample(position, d, 0.0, 0);
    return probe.rgb + (1.0 - probe.a) * distant;
}

// envLighting with local reflections at world position `position`.
vec3 envLightingAt(vec3 position, vec3 n, vec3 toEye, vec3 diffuseAlbedo, vec3 f0, float alpha, int ndf) {
    float nDotV = clamp(dot(n, toEye), 1e-4, 1.0);
    vec3 r = reflect(-toEye, n);
    vec2 ab = envBrdf(nDotV, alpha, ndf);
    vec3 specularAlbedo = f0 * ab.x + ab.y;
    vec3 specular = envPrefilteredAt(position, r, alpha, ndf) * specularAlbedo;
    vec3 diffuse = diffuseAlbedo * (1.0 - specularAlbedo) * envDiffuse(n);
    return diffuse + specular;
}
