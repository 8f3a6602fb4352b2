// IBL mode `fis`: filtered importance sampling (Colbert & Krivanek 2007, GPU Gems 3 ch. 20), the baseline of
// "Real-time Rendering of Glossy Materials with Regular Sampling" (CGI 2014, Sec. 4 Eq. 6-10 and Sec. 8), with
// the Kurt BRDF (environment/ibl/kurt_brdf.glsl). One deterministic Hammersley set shared by all pixels (as in C&K); each
// sample reads the MIP level lod = 0.5 log2(Omega_s / Omega_p) + 1, Omega_s = 1 / (N pdf) (Eq. 10), Omega_p the
// level-0 texel's solid angle at wi. CPU reference: engine/environment/ibl/ibl_estimators.cpp fisLobe.
// The diffuse term uses the SH irradiance (envDiffuse).
#include "environment/ibl/kurt_brdf.glsl"

vec3 fisLobeRadiance(KurtLobeGpu lobe, vec3 wo, mat3 shadingToWorld, vec3 r0) {
    int n = int(IBL_SAMPLES);
    float mx = lobe.roughness.x, my = lobe.roughness.y;
    float faceSize = kurtEnvironmentFaceSize();
    float texelArea = 4.0 / (faceSize * faceSize);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < n; ++i) {
        float u1 = (float(i) + 0.5) / float(n);
        float u2 = radicalInverse2(uint(i));
        vec3 h = kurtSampleHalfVector(1.0 - u1, u2, mx, my);
        vec3 wi = 2.0 * dot(wo, h) * h - wo;
        float oh = dot(wo, h);
        if (wi.z <= 0.0 || oh <= 0.0) continue;
        float pdf = kurtHalfVectorPdf(h, mx, my) / (4.0 * oh);   // Eq. 10
        vec3 wiWorld = shadingToWorld * wi;
        float d = cubeDistance(kurtMapDirection(wiWorld));
        float omegaS = 1.0 / (float(n) * pdf);
        float omegaP = texelArea / (d * d * d);
        float lod = max(0.5 * log2(omegaS / omegaP) + 1.0 + IBL_MIP_BIAS, 0.0);
        sum += kurtEnvironment(wiWorld, lod) * kurtLobe(wi, wo, lobe, r0) * (wi.z / pdf);   // Eq. 9
    }
    return lobe.roughness.z * sum / float(n);
}

#define KURT_LOBE_RADIANCE fisLobeRadiance
#include "environment/ibl/kurt_filtered_ibl.glsl"
