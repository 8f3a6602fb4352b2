// CPU mirror of shaders/image/tone_curves.glsl (tests compare the tone-mapping pass with it).
#pragma once
#include <glm/glm.hpp>

namespace glimmer::image {

enum class ToneCurve { Aces = 0, Neutral = 1, Agx = 2 };

// Scene-linear (exposed) Rec.709 -> display-linear [0, 1].
glm::vec3 applyToneCurve(ToneCurve curve, glm::vec3 color);
// Display-linear -> sRGB-encoded [0, 1] (IEC 61966-2-1).
glm::vec3 linearToSrgb(glm::vec3 color);

}  // namespace glimmer::image
