// Shared by the histogram and the exposure passes: 256 bins of log2 luminance over [-16, 16) EV (1/8 stop each);
// bin 0 also holds black and near-black pixels, which metering ignores.
const int HISTOGRAM_BINS = 256;
const float HISTOGRAM_MIN_EV = -16.0;
const float HISTOGRAM_EV_RANGE = 32.0;
#include "common/bindings.glsl"
layout(std430, binding = BINDING_EXPOSURE_HISTOGRAM) buffer LuminanceHistogram { uint u_histogram[HISTOGRAM_BINS]; };
layout(std430, binding = BINDING_EXPOSURE_STATE) buffer ExposureState { float u_meteredEv; float u_targetEv; };
