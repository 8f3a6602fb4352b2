// KHR_lights_punctual's recommended falloffs (the extension's README, "Range Property" and "Spot"), on the CPU
// for tests and documentation; shaders/frame/lighting.frag evaluates the same formulas per pixel.
#include <algorithm>
#include <cmath>

#include "scene/scene.h"

namespace glimmer {

float spotAttenuation(float cosAngle, float innerConeAngle, float outerConeAngle) {
    float cosOuter = std::cos(outerConeAngle), cosInner = std::cos(innerConeAngle);
    float scale = 1.0f / std::max(0.001f, cosInner - cosOuter);
    float t = std::clamp((cosAngle - cosOuter) * scale, 0.0f, 1.0f);
    return t * t;
}

float rangeWindow(float distance, float range) {
    if (range <= 0.0f) return 1.0f;
    float r = distance / range;
    float w = std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
    return w * w;
}

}  // namespace glimmer
