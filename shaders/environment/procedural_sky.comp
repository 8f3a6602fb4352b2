// The default environment: an analytic clear sky (zenith-to-horizon gradient, a glow around the sun, a dim ground)
// with a sun disk whose radiance delivers the scene's directional-light irradiance (disk radiance = E / solid
// angle). Not a physical sky model (no Preetham / Hosek coefficients); it is a smooth, colourful HDR test
// environment that needs no files. Writes level 0 of a cube.
#include "environment/env_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(rgba32f, binding = 0) uniform writeonly imageCube u_cube;
layout(location = 0) uniform int u_size;
layout(location = 1) uniform vec3 u_sunDirection;    // unit, towards the sun
layout(location = 2) uniform vec3 u_sunIrradiance;   // irradiance at normal incidence (colour x intensity)
layout(location = 3) uniform int u_drawSun;          // 0: sky only (the sun is an analytic light)

const float SUN_ANGULAR_RADIUS = 0.0175;   // 1 degree: a few texels wide at face size 256 (the real sun is 0.27)

vec3 skyRadiance(vec3 d) {
    const vec3 zenith = vec3(0.10, 0.22, 0.55);
    const vec3 horizon = vec3(0.55, 0.62, 0.70);
    const vec3 ground = vec3(0.10, 0.09, 0.08);
    float up = d.y;
    vec3 sky = mix(horizon, zenith, sqrt(max(up, 0.0)));
    // Forward-scattering glow, tinted by the sun's colour and fading with its height.
    vec3 sunTint = u_sunIrradiance / max(max(u_sunIrradiance.r, max(u_sunIrradiance.g, u_sunIrradiance.b)), 1e-6);
    float cosSun = max(dot(d, u_sunDirection), 0.0);
    sky += sunTint * (0.6 * pow(cosSun, 64.0) + 0.15 * pow(cosSun, 4.0));
    // Soft horizon line over about one degree.
    return mix(ground, sky, smoothstep(-0.02, 0.02, up));
}

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= u_size || id.y >= u_size) return;
    vec3 d = cubeDirection(id.z, vec2(id.xy) + 0.5, u_size);
    vec3 radiance = skyRadiance(d);
    if (u_drawSun != 0) {
        float solidAngle = 2.0 * PI * (1.0 - cos(SUN_ANGULAR_RADIUS));
        float angle = acos(clamp(dot(d, u_sunDirection), -1.0, 1.0));
        // Coverage of the disk edge over one texel's angular size (anti-aliased), so the disk's integral stays E.
        float texelAngle = 2.0 / float(u_size);
        float coverage = clamp((SUN_ANGULAR_RADIUS - angle) / texelAngle + 0.5, 0.0, 1.0);
        radiance += coverage * u_sunIrradiance / solidAngle;
    }
    imageStore(u_cube, id, vec4(radiance, 1.0));
}
