// What the glint method produced in the lighting pass, before any clamp (render/frame/method_output_check.h reads it):
// NaN, Inf or negative D, non-finite or negative radiance, and at a sparse sample of pixels how often D exceeds
// the smooth NDF by far. Each pixel tallies locally and adds to the counters with atomics only when it has
// something to add: a good method costs a few comparisons per light, and atomics at one pixel in 16.
layout(std430, binding = BINDING_METHOD_OUTPUT) buffer MethodOutputBlock {
    uint u_methodOutput[8];   // sampled, far above smooth, non-finite D, negative D, non-finite / negative radiance
};

struct MethodOutputTally {
    uint sampled, farAboveSmooth, nonFiniteD, negativeD;
};

MethodOutputTally methodOutputTally() { return MethodOutputTally(0u, 0u, 0u, 0u); }

// One pixel in 16 measures D against D_smooth (render/frame/method_output_check.h says why 4 x + 1): whole 4x4
// blocks, one block in 4 along x and y, so that llvmpipe's 4x4 SIMD blocks take the branch together (a scattered
// pattern made every block evaluate D_smooth: +3% of a deliot2023 frame's CPU time).
bool methodOutputSampled(ivec2 pixel) { return ((pixel.x | pixel.y) & 12) == 0; }

bool nonFinite(float x) { return isnan(x) || isinf(x); }

void tallyD(inout MethodOutputTally t, float D, bool sampled, vec3 h, float alpha, int ndf) {
    if (nonFinite(D)) t.nonFiniteD += 1u;
    else if (D < 0.0) t.negativeD += 1u;
    if (sampled) {
        t.sampled += 1u;
        if (!nonFinite(D) && D > 4.0 * D_smooth(h, alpha, ndf) + 1.0) t.farAboveSmooth += 1u;
    }
}

// The RGB NDF of methods with per-glint colours: each channel must be finite and non-negative; the far-above
// test uses their mean (the D the lighting pass reports).
void tallyColorD(inout MethodOutputTally t, vec3 colorD, bool sampled, vec3 h, float alpha, int ndf) {
    bool bad = nonFinite(colorD.x) || nonFinite(colorD.y) || nonFinite(colorD.z);
    if (bad) t.nonFiniteD += 1u;
    else if (min(colorD.x, min(colorD.y, colorD.z)) < 0.0) t.negativeD += 1u;
    if (sampled) {
        t.sampled += 1u;
        if (!bad && dot(colorD, vec3(1.0 / 3.0)) > 4.0 * D_smooth(h, alpha, ndf) + 1.0) t.farAboveSmooth += 1u;
    }
}

// Adds the pixel's tally and its final radiance (before the clamp) to the counters.
void flushMethodOutput(MethodOutputTally t, vec3 radiance) {
    uint nonFiniteRadiance = uint(nonFinite(radiance.x)) + uint(nonFinite(radiance.y)) + uint(nonFinite(radiance.z));
    uint negativeRadiance = uint(radiance.x < 0.0) + uint(radiance.y < 0.0) + uint(radiance.z < 0.0);
    if (t.sampled != 0u) {
        atomicAdd(u_methodOutput[0], t.sampled);
        if (t.farAboveSmooth != 0u) atomicAdd(u_methodOutput[1], t.farAboveSmooth);
    }
    if (t.nonFiniteD != 0u) atomicAdd(u_methodOutput[2], t.nonFiniteD);
    if (t.negativeD != 0u) atomicAdd(u_methodOutput[3], t.negativeD);
    if (nonFiniteRadiance != 0u) atomicAdd(u_methodOutput[4], nonFiniteRadiance);
    if (negativeRadiance != 0u) atomicAdd(u_methodOutput[5], negativeRadiance);
}
