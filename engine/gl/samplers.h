// Sampler objects shared by the full-screen passes.
#pragma once
#include "gl/handles.h"

namespace glimmer::gl {

// Bilinear, no mipmaps, clamped at the edges, no depth compare: for passes that read a target at fractional
// positions (TAA history, bloom levels, GTAO's depth).
Sampler createLinearClampSampler();

}  // namespace glimmer::gl
