// KHR_lights_punctual's recommended falloffs (the extension's README, "Range Property" and "Spot"), on the CPU
// for tests and documentation; shaders/frame/lighting.frag evaluates the same formulas per pixel. Also the lights'
// sizes and the GPU order of punctual and area lights.
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

float Light::area() const {
    switch (type) {
        case LightType::Rect: return width * height;
        case LightType::Disk: return 3.14159265f * radius * radius;
        case LightType::Sphere: return 4.0f * 3.14159265f * radius * radius;
        default: return 0.0f;
    }
}

float Light::radianceScale() const {
    if (type == LightType::Sphere) return intensity / std::max(3.14159265f * radius * radius, 1e-12f);
    if (isArea()) return intensity / std::max(area(), 1e-12f);
    return intensity;
}

std::vector<size_t> gpuLightOrder(const std::vector<Light>& lights) {
    std::vector<size_t> order;
    for (int area = 0; area < 2; ++area)
        for (size_t i = 0; i < lights.size(); ++i)
            if (lights[i].isArea() == (area == 1)) order.push_back(i);
    return order;
}

float rangeWindow(float distance, float range) {
    if (range <= 0.0f) return 1.0f;
    float r = distance / range;
    float w = std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
    return w * w;
}

}  // namespace glimmer
