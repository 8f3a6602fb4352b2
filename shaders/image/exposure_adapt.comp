// Auto exposure, step 2 (one workgroup): the mean log2 luminance of the pixels between the 40th and the 95th
// percentile of the histogram (the dark half and the brightest few per cent - sky, sun glints - do not meter),
// mapped to middle grey 0.18 (the usual reflected-light meter calibration). The metered value moves towards
// this target with weight u_adaptation per frame (1 - exp(-dt * speed) in the window; 1 offscreen, where the
// exposure is that of the frame itself). Clears the histogram for the next frame.
#include "image/exposure_common.glsl"
layout(local_size_x = 256) in;
layout(location = 0) uniform float u_adaptation;   // 0..1
layout(location = 1) uniform float u_lowPercentile;
layout(location = 2) uniform float u_highPercentile;

shared uint s_counts[HISTOGRAM_BINS];

void main() {
    uint bin = gl_LocalInvocationIndex;
    s_counts[bin] = bin == 0u ? 0u : u_histogram[bin];   // black pixels do not meter
    u_histogram[bin] = 0u;
    barrier();
    if (bin != 0u) return;
    uint total = 0u;
    for (int i = 0; i < HISTOGRAM_BINS; ++i) total += s_counts[i];
    if (total == 0u) return;   // an all-black frame keeps the previous exposure
    float low = u_lowPercentile * float(total), high = u_highPercentile * float(total);
    float below = 0.0, weight = 0.0, evSum = 0.0;
    for (int i = 1; i < HISTOGRAM_BINS; ++i) {
        float count = float(s_counts[i]);
        // The part of this bin's pixels that lies inside [low, high] of the sorted luminances.
        float inside = max(0.0, min(below + count, high) - max(below, low));
        float ev = HISTOGRAM_MIN_EV + (float(i) + 0.5) / float(HISTOGRAM_BINS) * HISTOGRAM_EV_RANGE;
        evSum += inside * ev;
        weight += inside;
        below += count;
    }
    float meanEv = weight > 0.0 ? evSum / weight : 0.0;
    u_targetEv = clamp(log2(0.18) - meanEv, -20.0, 20.0);
    u_meteredEv = mix(u_meteredEv, u_targetEv, clamp(u_adaptation, 0.0, 1.0));
}
