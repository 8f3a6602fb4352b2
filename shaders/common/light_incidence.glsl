// Direction towards a light and the irradiance it delivers at normal incidence (directional: irradiance;
// point: intensity / distance^2). The forward passes' copy of the lighting pass's rule (lighting.frag).
void lightIncidence(GpuLight light, vec3 position, out vec3 towardLight, out vec3 irradiance) {
    vec3 radiant = light.colorIntensity.rgb * light.colorIntensity.a;
    if (light.vectorType.w < 0.5) {
        towardLight = normalize(light.vectorType.xyz);
        irradiance = radiant;
    } else {
        vec3 d = light.vectorType.xyz - position;
        float distance2 = max(dot(d, d), 1e-8);
        towardLight = d * inversesqrt(distance2);
        irradiance = radiant / distance2;
    }
}
