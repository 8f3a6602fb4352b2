#include "render/image/tone_curves.h"

#include <algorithm>
#include <cmath>

namespace glimmer::image {

namespace {

glm::vec3 saturate(glm::vec3 c) { return glm::clamp(c, glm::vec3(0.0f), glm::vec3(1.0f)); }

glm::vec3 aces(glm::vec3 x) {   // Narkowicz 2015
    return saturate((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f));
}

glm::vec3 neutral(glm::vec3 color) {   // Khronos PBR Neutral
    const float start = 0.8f - 0.04f, desaturation = 0.15f;
    float lowest = std::min({color.x, color.y, color.z});
    float toe = lowest < 0.08f ? lowest - 6.25f * lowest * lowest : 0.04f;
    color -= toe;
    float peak = std::max({color.x, color.y, color.z});
    if (peak < start) return saturate(color);
    float d = 1.0f - start;
    float newPeak = 1.0f - d * d / (peak + d - start);
    color *= newPeak / peak;
    float towardWhite = 1.0f - 1.0f / (desaturation * (peak - newPeak) + 1.0f);
    return saturate(glm::mix(color, glm::vec3(newPeak), towardWhite));
}

glm::vec3 agx(glm::vec3 color) {   // AgX, minimal form (polynomial sigmoid)
    // Column-major, as in the shader: inset[c] is column c.
    const glm::mat3 inset(0.842479062253094f, 0.0423282422610123f, 0.0423756549057051f,
                          0.0784335999999992f, 0.878468636469772f, 0.0784336f,
                          0.0792237451477643f, 0.0791661274605434f, 0.879142973793104f);
    const glm::mat3 outset(1.19687900512017f, -0.0528968517574562f, -0.0529716355144438f,
                           -0.0980208811401368f, 1.15190312990417f, -0.0980434501171241f,
                           -0.0990297440797205f, -0.0989611768448433f, 1.15107367264116f);
    const float minEv = -12.47393f, maxEv = 4.026069f;
    glm::vec3 x = inset * glm::max(color, glm::vec3(0.0f));
    for (int i = 0; i < 3; ++i) {
        float v = std::clamp((std::log2(std::max(x[i], 1e-10f)) - minEv) / (maxEv - minEv), 0.0f, 1.0f);
        float v2 = v * v, v4 = v2 * v2;
        x[i] = 15.5f * v4 * v2 - 40.14f * v4 * v + 31.96f * v4 - 6.868f * v2 * v + 0.4298f * v2 + 0.1191f * v -
               0.00232f;
    }
    x = outset * x;
    for (int i = 0; i < 3; ++i) x[i] = std::pow(std::max(x[i], 0.0f), 2.2f);
    return saturate(x);
}

}  // namespace

glm::vec3 applyToneCurve(ToneCurve curve, glm::vec3 color) {
    switch (curve) {
        case ToneCurve::Neutral: return neutral(color);
        case ToneCurve::Agx: return agx(color);
        case ToneCurve::Aces: break;
    }
    return aces(color);
}

glm::vec3 linearToSrgb(glm::vec3 c) {
    c = saturate(c);
    for (int i = 0; i < 3; ++i)
        c[i] = c[i] < 0.0031308f ? 12.92f * c[i] : 1.055f * std::pow(c[i], 1.0f / 2.4f) - 0.055f;
    return c;
}

}  // namespace glimmer::image
