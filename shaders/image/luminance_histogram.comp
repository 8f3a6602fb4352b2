// Auto exposure, step 1: a histogram of log2 luminance of the HDR frame (the radiance after TAA, before bloom).
// Per-workgroup bins in shared memory, then one atomic add per bin into the global histogram.
#include "image/exposure_common.glsl"
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = UNIT_EXPOSURE_HDR) uniform sampler2D t_hdr;
layout(location = 0) uniform ivec2 u_size;

shared uint s_bins[HISTOGRAM_BINS];

void main() {
    uint local = gl_LocalInvocationIndex;
    s_bins[local] = 0u;
    barrier();
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(pixel, u_size))) {
        float luminance = dot(texelFetch(t_hdr, pixel, 0).rgb, vec3(0.2126, 0.7152, 0.0722));
        int bin = 0;
        if (luminance > exp2(HISTOGRAM_MIN_EV) && !isinf(luminance) && !isnan(luminance))
            bin = clamp(int((log2(luminance) - HISTOGRAM_MIN_EV) / HISTOGRAM_EV_RANGE * float(HISTOGRAM_BINS)), 1,
                        HISTOGRAM_BINS - 1);
        atomicAdd(s_bins[bin], 1u);
    }
    barrier();
    if (s_bins[local] != 0u) atomicAdd(u_histogram[local], s_bins[local]);
}
