// Direction towards a light and the irradiance it delivers at normal incidence (KHR_lights_punctual: point and
// spot intensity / d^2 times the recommended range window; spot times the cone falloff t^2). A visibility factor
// (shadows) multiplies the result. One rule for the lighting pass, the shadow mask and the forward passes.
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
        float range = light.spotOffsetRange.y;
        if (range > 0.0) {
            float r2 = distance2 / (range * range);
            float window = clamp(1.0 - r2 * r2, 0.0, 1.0);
            irradiance *= window * window;
        }
        if (light.vectorType.w > 1.5) {
            float t = clamp(dot(light.spotAxisScale.xyz, -towardLight) * light.spotAxisScale.w + light.spotOffsetRange.x,
                            0.0, 1.0);
            irradiance *= t * t;
        }
    }
}
