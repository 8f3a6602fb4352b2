// Method `reference`: the exact discrete-facet reference of the glint material (issue 36). Nothing is estimated
// here: the CPU (engine/reference/discrete_facets/) counted, for every glinty pixel and every light, the facets
// of a fixed realization of the material in the pixel's UV footprint whose normal reflects that light's half
// vector, and uploaded D_est = D(h) x (weighted count) / (density x P(h)), whose expectation is D(h) exactly
// (facet_estimator.h). This file returns the value of the light being shaded, so the lighting pass applies
// Fresnel, masking, shadows and irradiance to it like to any method's NDF.
// Lights of a size (area lights, point lights of a radius; the sun's disk with reference.light_extent=all): the CPU
// integrates each facet's lobe over the light (engine/reference/discrete_facets/extended_lights.h) and uploads
// D_est = (N / M) x D(h_centre), so the lighting pass's fallback for area lights (that value over D_smooth at the
// centre, times the smooth LTC specular) multiplies the specular by the facets' glint factor N / M. Layer k is the
// lighting pass's light k (gpuLightOrder).
#define GLINT_COLOR_D 1   // per-facet colours (GlintMaterial color, colorVariation)

// Layer k: light k's D_est per colour channel; a = 1 where the CPU evaluated the pixel.
layout(binding = UNIT_METHOD_FIRST) uniform sampler2DArray u_referenceD;

struct GlintPixel { int unused; };

GlintPixel glintSetup(GlintSurface s) {
    GlintPixel px;
    px.unused = 0;
    return px;
}

// The index of the frame's light that arrives from wi at this pixel (the lighting pass shades one light at a
// time and passes its direction), or -1 when wi is no light's (a Monte Carlo IBL mode's sample direction).
int referenceLightIndex(GlintSurface s, vec3 wi) {
#ifdef GLIMMER_LIGHTING_PASS
    int count = min(int(u_exposure.y), textureSize(u_referenceD, 0).z);
    int best = -1;
    float bestCosine = 0.999999;
    for (int k = 0; k < count; ++k) {
        vec3 towardLight, irradiance;
        lightIncidence(u_lights[k], s.position, towardLight, irradiance);
        vec3 w = vec3(dot(towardLight, s.t), dot(towardLight, s.b), dot(towardLight, s.n));
        float c = dot(w, wi);
        if (c > bestCosine) {
            bestCosine = c;
            best = k;
        }
    }
    return best;
#else
    return -1;
#endif
}

vec3 glintColorD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    int k = referenceLightIndex(s, wi);
    if (k < 0) return vec3(D_smooth(h, s.alpha, s.ndf));   // not one of the lights the CPU counted for
    vec4 texel = texelFetch(u_referenceD, ivec3(s.pixel, k), 0);
    return texel.a > 0.5 ? texel.rgb : vec3(D_smooth(h, s.alpha, s.ndf));
}

float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    return dot(glintColorD(px, s, h, wi, wo), vec3(1.0 / 3.0));
}

vec4 glintFootprintAOV(GlintPixel px, GlintSurface s) {
    FootprintEllipse e = footprintEllipse(s.duvdx, s.duvdy);
    return vec4(e.major / e.minor, log2(e.minor), e.major, e.minor);
}

vec4 glintExtraAOV(GlintPixel px, GlintSurface s) {
    return texelFetch(u_referenceD, ivec3(s.pixel, 0), 0);
}
