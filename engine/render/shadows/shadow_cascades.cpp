#include "render/shadows/shadow_cascades.h"

#include <algorithm>
#include <cmath>

namespace glimmer {

std::vector<float> cascadeSplits(float nearPlane, float farDistance, int count, float lambda) {
    count = std::max(count, 1);
    nearPlane = std::max(nearPlane, 1e-4f);
    farDistance = std::max(farDistance, nearPlane * 1.001f);
    std::vector<float> splits(size_t(count) + 1);
    for (int i = 0; i <= count; ++i) {
        float t = float(i) / float(count);
        float logarithmic = nearPlane * std::pow(farDistance / nearPlane, t);
        float uniform = nearPlane + (farDistance - nearPlane) * t;
        splits[size_t(i)] = lambda * logarithmic + (1.0f - lambda) * uniform;
    }
    splits.front() = nearPlane;
    splits.back() = farDistance;
    return splits;
}

glm::mat3 lightBasis(const glm::vec3& towardLight) {
    glm::vec3 w = glm::normalize(towardLight);
    // Any fixed reference axis not parallel to w; the choice only has to be the same every frame.
    glm::vec3 reference = std::abs(w.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    glm::vec3 u = glm::normalize(glm::cross(reference, w));
    glm::vec3 v = glm::cross(w, u);   // u x v = w
    return glm::transpose(glm::mat3(u, v, w));
}

BoundingSphere cascadeSphere(const glm::vec3& eye, float verticalFovDegrees, float aspect, float sliceFar) {
    float tanHalf = std::tan(glm::radians(verticalFovDegrees) * 0.5f);
    float cornerScale = std::sqrt(1.0f + tanHalf * tanHalf * (1.0f + aspect * aspect));
    return {eye, sliceFar * cornerScale};
}

CascadeWindow fitCascadeWindow(const LightRect& needed, float sphereRadius, float margin, int mapSize) {
    CascadeWindow window;
    window.mapSize = std::max(mapSize, 1);
    window.halfExtent = std::ceil(sphereRadius * (1.0f + margin) * 64.0f) / 64.0f;
    float texel = window.texelSize();
    glm::vec2 center = needed.empty() ? glm::vec2(0.0f) : 0.5f * (needed.min + needed.max);
    window.center = glm::round(center / texel) * texel;
    return window;
}

LightRect neededRect(const glm::mat3& basis, const BoundingSphere& sphere, const LightRect& sceneRect) {
    glm::vec3 c = basis * sphere.center;
    LightRect rect{glm::vec2(c) - sphere.radius, glm::vec2(c) + sphere.radius};
    rect.min = glm::max(rect.min, sceneRect.min);
    rect.max = glm::min(rect.max, sceneRect.max);
    return rect;
}

bool windowCovers(const CascadeWindow& window, const LightRect& needed, float guardTexels) {
    if (needed.empty()) return true;
    float reach = window.halfExtent - guardTexels * window.texelSize();
    glm::vec2 lo = window.center - reach, hi = window.center + reach;
    return needed.min.x >= lo.x && needed.min.y >= lo.y && needed.max.x <= hi.x && needed.max.y <= hi.y;
}

glm::mat4 cascadeViewProjection(const glm::mat3& basis, const CascadeWindow& window, float depthMin, float depthMax) {
    float depthRange = std::max(depthMax - depthMin, 1e-3f);
    glm::mat4 toLight(basis);   // rotation; column 3 stays (0, 0, 0, 1)
    glm::mat4 toClip(1.0f);
    toClip[0][0] = 1.0f / window.halfExtent;
    toClip[1][1] = 1.0f / window.halfExtent;
    toClip[2][2] = 1.0f / depthRange;
    toClip[3][0] = -window.center.x / window.halfExtent;
    toClip[3][1] = -window.center.y / window.halfExtent;
    toClip[3][2] = -depthMin / depthRange;
    return toClip * toLight;
}

}  // namespace glimmer
