#include "render/image/halton_jitter.h"

#include <algorithm>
#include <cmath>

namespace glimmer::image {

float radicalInverse(unsigned index, unsigned base) {
    float result = 0.0f, digitWeight = 1.0f / float(base);
    for (; index > 0; index /= base, digitWeight /= float(base)) result += float(index % base) * digitWeight;
    return result;
}

int jitterPhases(float upscaleRatio) {
    float r = std::max(upscaleRatio, 1.0f);
    return std::max(kJitterSamples, int(std::ceil(8.0f * r * r - 1e-4f)));
}

glm::vec2 haltonJitter(unsigned framesSinceReset, int phases) {
    if (framesSinceReset == 0) return glm::vec2(0.0f);
    // Indices 1..phases (index 0 of Halton is the origin, a corner of the pixel, not its centre).
    unsigned index = (framesSinceReset - 1) % unsigned(std::max(phases, 1)) + 1;
    return glm::vec2(radicalInverse(index, 2), radicalInverse(index, 3)) - 0.5f;
}

glm::mat4 jitteredProjection(const glm::mat4& projection, glm::vec2 jitterPixels, glm::ivec2 size) {
    glm::mat4 translate(1.0f);
    translate[3][0] = 2.0f * jitterPixels.x / float(size.x);
    translate[3][1] = 2.0f * jitterPixels.y / float(size.y);
    return translate * projection;
}

}  // namespace glimmer::image
