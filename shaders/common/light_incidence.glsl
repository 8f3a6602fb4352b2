// Direction towards a light and the irradiance it delivers at normal incidence (KHR_lights_punctual: point and
// spot intensity / d^2 times the recommended range window; spot times the cone falloff t^2). A visibility factor
// (shadows) multiplies the result. One rule for the lighting pass, the shadow mask and the forward passes.
// Area lights (type >= 3): the direction to the centre and the irradiance of a point light of their intensity
// (rect and disk: times the cosine at the emitter, zero behind a one-sided one). The lighting pass shades them by
// their LTC integrals instead (lights/area_light.glsl); this is what the shadow mask and the forward passes use.
void lightIncidence(GpuLight light, vec3 position, out vec3 towardLight, out vec3 irradiance) {
    if (light.vectorType.w < 0.5) {
        towardLight = normalize(light.vectorType.xyz);
        irradiance = light.colorIntensity.rgb * light.colorIntensity.a;
        return;
    }
    vec3 d = light.vectorType.xyz - position;
    float distance2 = max(dot(d, d), 1e-8);
    towardLight = d * inversesqrt(distance2);
    // Intensity: colorIntensity.a for point and spot lights; area lights keep their radiance there and the
    // intensity in spotOffsetRange.w.
    irradiance = light.colorIntensity.rgb * (light.vectorType.w > 2.5 ? light.spotOffsetRange.w : light.colorIntensity.a)
                 / distance2;
    float range = light.spotOffsetRange.y;
    if (range > 0.0) {
        float r2 = distance2 / (range * range);
        float window = clamp(1.0 - r2 * r2, 0.0, 1.0);
        irradiance *= window * window;
    }
    if (light.vectorType.w > 2.5 && light.vectorType.w < 4.5) {   // rect, disk: a Lambertian emitter's cosine
        vec3 normal = cross(light.areaU.xyz, light.areaV.xyz);
        float cosine = dot(normal, -towardLight) * inversesqrt(max(dot(normal, normal), 1e-30));
        irradiance *= light.areaU.w > 0.5 ? abs(cosine) : max(cosine, 0.0);
    } else if (light.vectorType.w > 1.5 && light.vectorType.w < 2.5) {
        float t = clamp(dot(light.spotAxisScale.xyz, -towardLight) * light.spotAxisScale.w + light.spotOffsetRange.x,
                        0.0, 1.0);
        irradiance *= t * t;
    }
}
