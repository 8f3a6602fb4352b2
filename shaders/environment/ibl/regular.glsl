// IBL mode `regular`: "Real-time Rendering of Glossy Materials with Regular Sampling" (CGI 2014), Sec. 5-7, with
// the Kurt BRDF of Sec. 4 (environment/ibl/kurt_brdf.glsl). The pattern of each lobe (Sec. 5) comes from the CPU
// (engine/environment/ibl/regular_pattern.cpp); this file evaluates the paper's EvaluateSpecularLobe per lobe:
// per-pixel ellipse area (Eq. 14-15), per-sample MIP level (Eq. 16), constant pdf (Eq. 17-18), Eq. 9 sum.
// CPU reference: engine/environment/ibl/ibl_estimators.cpp regularLobe.
// Environment: the scene's map (box chain or re-filtered, ibl.pyramid) or the object's own map (ibl.object_maps,
// Sec. 3), see kurtEnvironment in environment/ibl/kurt_brdf.glsl. Deviations: the diffuse term kd/pi * irradiance uses the SH irradiance (envDiffuse); glinty materials get the smooth Kurt lobe.
#include "environment/ibl/kurt_brdf.glsl"

// Eq. 14-15 and A = pi u v: the lobe's elliptical cross-section at unit distance, from the extreme half vectors
// at the xi0 border along t and b reflected about wo (angles capped below 90 degrees at grazing views).
float regularLobeArea(vec3 wo, float mx, float my, float xi0) {
    float border = sqrt(-log(xi0));
    float tu = atan(border * mx), tv = atan(border * my);
    vec3 hU = vec3(sin(tu), 0.0, cos(tu)), hV = vec3(0.0, sin(tv), cos(tv));
    vec3 wC = vec3(-wo.xy, wo.z);
    vec3 wU = 2.0 * dot(wo, hU) * hU - wo, wV = 2.0 * dot(wo, hV) * hV - wo;
    const float cap = 0.5 * PI - 1e-3;
    float aU = min(acos(clamp(dot(wC, wU), -1.0, 1.0)), cap);
    float aV = min(acos(clamp(dot(wC, wV), -1.0, 1.0)), cap);
    return PI * tan(aU) * tan(aV);
}

vec3 regularLobeRadiance(KurtLobeGpu lobe, vec3 wo, mat3 shadingToWorld, vec3 r0) {
    int first = int(lobe.pattern.x), count = int(lobe.pattern.y);
    float pdfConstant = lobe.pattern.z, xi0 = lobe.pattern.w;
    if (count <= 0 || pdfConstant <= 0.0) return vec3(0.0);
    float area = regularLobeArea(wo, lobe.roughness.x, lobe.roughness.y, xi0);
    float faceSize = kurtEnvironmentFaceSize();
    float texelsPerSampleBase = area * faceSize * faceSize / (4.0 * float(count));   // Eq. 16, A N / (4 n)
    vec3 sum = vec3(0.0);
    for (int i = 0; i < count; ++i) {
        vec3 h = u_kurtHalfVectors[first + i].xyz;
        vec3 wi = 2.0 * dot(wo, h) * h - wo;
        float ih = dot(wi, h);
        if (wi.z <= 0.0 || ih <= 0.0) continue;
        vec3 wiWorld = shadingToWorld * wi;
        // Eq. 16: cube distortion |wi| / |wi|_inf (in the map's frame) and half-vector term 1 / (wi.h).
        float texels = texelsPerSampleBase * cubeDistance(kurtMapDirection(wiWorld)) / max(ih, 1e-4);
        float lod = max(0.5 * log2(max(texels, 1e-12)) + IBL_MIP_BIAS, 0.0);   // log4
        float pdf = pdfConstant / (4.0 * ih);   // Eq. 17-18
        sum += kurtEnvironment(wiWorld, lod) * kurtLobe(wi, wo, lobe, r0) * (wi.z / pdf);
    }
    return lobe.roughness.z * sum / float(count);
}

#define KURT_LOBE_RADIANCE regularLobeRadiance
#include "environment/ibl/kurt_filtered_ibl.glsl"
