// Sub-pixel jitter of the projection for TAA: the Halton (2, 3) sequence, in pixels of the rendered (internal)
// image, in [-0.5, 0.5). 16 phases at native resolution; TAA upsampling uses more (jitterPhases). Sample 0 (the
// first frame after a history reset) is unjittered, so a one-frame TAA render equals aa=off.
#pragma once
#include <glm/glm.hpp>

namespace glimmer::image {

constexpr int kJitterSamples = 16;

// Radical inverse of `index` in `base` (the Halton sequence's coordinate).
float radicalInverse(unsigned index, unsigned base);
// Phases of the cycle for an upscale ratio (output / internal pixels per axis, the larger): max(16, ceil(8 r^2)),
// so each output pixel still sees about 8 samples land in it per cycle (the count AMD FSR 2 describes); 16 at
// r = 1 (the native TAA's), 32 at r = 2, 128 at r = 4.
int jitterPhases(float upscaleRatio);
// Jitter of the frame `framesSinceReset` frames after the last reset, in a cycle of `phases` samples.
glm::vec2 haltonJitter(unsigned framesSinceReset, int phases = kJitterSamples);
// `projection` translated by `jitterPixels` on a viewport of `size` pixels: a pure screen-space translation
// (clip.xy += clip.w * 2 jitter / size), so screen-space derivatives of anything interpolated are unchanged.
glm::mat4 jitteredProjection(const glm::mat4& projection, glm::vec2 jitterPixels, glm::ivec2 size);

}  // namespace glimmer::image
