// Environment glints (Kneiphof & Klein 2025, "Real-time Image-based Lighting of Glints", EGSR 2025), the lookups of
// the lighting pass: the radiance levels (a storage buffer written by shaders/environment/glint_levels.comp) and
// the prefiltered indicator weights of the distant environment and of the reflection probes
// (engine/environment/environment_glints.h), blended like the radiance (common/ibl.glsl): probe weights are
// premultiplied by its coverage, so w = w_probe + (1 - coverage) w_distant.
#include "common/bindings.glsl"

layout(std430, binding = BINDING_ENV_GLINTS) readonly buffer EnvGlintBlock {
    vec4 u_envGlintLevel[2];   // radiance of levels 0..7 (level 0 = 0), before env.intensity
    vec4 u_envGlintRange;      // x darkest luminance above the black level, y brightest, z black level
    ivec4 u_envGlintInfo;      // x levels K (0: none), y indicator slices (K = 4: 1, K = 8: 2), z probes with weights
};
// Layer = slice x 2 + NDF; level k holds sqrt(alpha) = k / 5 (as the probes' mip chain).
layout(binding = UNIT_ENV_GLINT_WEIGHTS) uniform samplerCubeArray u_envGlintWeights;
// Layer = (probe x 2 + slice) x 2 + NDF, premultiplied by the probe's coverage.
layout(binding = UNIT_PROBE_GLINT_WEIGHTS) uniform samplerCubeArray u_probeGlintWeights;

const float ENV_GLINT_LAST_LEVEL = 5.0;   // EnvironmentGlints::kLevels - 1

// The levels and the weights of the lobe around world direction r at roughness alpha, at world `position` (probes).
GlintEnvironment envGlintsAt(vec3 position, vec3 r, float alpha, int ndf) {
    GlintEnvironment env;
    env.levels = u_envGlintInfo.x;
    for (int i = 0; i < 8; ++i) {
        env.radiance[i] = u_envParams.x * u_envGlintLevel[i >> 2][i & 3];
        env.weight[i] = 0.0;
    }
    env.ndfIntegral = 0.0;
    if (env.levels <= 0) return env;
    float lod = sqrt(clamp(alpha, 0.0, 1.0)) * ENV_GLINT_LAST_LEVEL;
    vec3 d = envDirection(r);
    vec4 w0 = textureLod(u_envGlintWeights, vec4(d, float(ndf)), lod);
    vec4 w1 = u_envGlintInfo.y > 1 ? textureLod(u_envGlintWeights, vec4(d, float(2 + ndf)), lod) : vec4(0.0);
    // The probe whose box holds the point, as envPrefilteredAt reads it (common/ibl.glsl).
    if (u_probeParams.x > 0.5 && u_envGlintInfo.z > 0) {
        float weight;
        int i = probeAt(position, weight);
        if (i >= 0 && weight > 0.0 && i < u_envGlintInfo.z) {
            vec3 pd = probeDirection(i, position, r);
            float coverage = weight * textureLod(u_probeSpecular, vec4(pd, float(2 * i + ndf)), lod).a;
            int base = (2 * i) * 2 + ndf;
            w0 = weight * textureLod(u_probeGlintWeights, vec4(pd, float(base)), lod) + (1.0 - coverage) * w0;
            if (u_envGlintInfo.y > 1)
                w1 = weight * textureLod(u_probeGlintWeights, vec4(pd, float(base + 2)), lod) + (1.0 - coverage) * w1;
        }
    }
    env.weight[1] = w0.x, env.weight[2] = w0.y, env.weight[3] = w0.z, env.weight[4] = w0.w;
    env.weight[5] = w1.x, env.weight[6] = w1.y, env.weight[7] = w1.z;
    float rest = 1.0;
    for (int i = 1; i < 8; ++i) {
        env.weight[i] = i < env.levels ? clamp(env.weight[i], 0.0, 1.0) : 0.0;
        rest -= env.weight[i];
    }
    env.weight[0] = max(rest, 0.0);
    return env;
}
