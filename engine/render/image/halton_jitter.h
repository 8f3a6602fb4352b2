// Sub-pixel jitter of the projection for TAA: the Halton (2, 3) sequence, 16 samples, in pixels in [-0.5, 0.5).
// Sample 0 (the first frame after a history reset) is unjittered, so a one-frame TAA render equals aa=off.
#pragma once
#include <glm/glm.hpp>

namespace glimmer::image {

constexpr int kJitterSamples = 16;

// Radical inverse of `index` in `base` (the Halton sequence's coordinate).
float radicalInverse(unsigned index, unsigned base);
// Jitter of the frame `framesSinceReset` frames after the last reset.
glm::vec2 haltonJitter(unsigned framesSinceReset);
// `projection` translated by `jitterPixels` on a viewport of `size` pixels: a pure screen-space translation
// (clip.xy += clip.w * 2 jitter / size), so screen-space derivatives of anything interpolated are unchanged.
glm::mat4 jitteredProjection(const glm::mat4& projection, glm::vec2 jitterPixels, glm::ivec2 size);

}  // namespace glimmer::image
