#include "render/aov.h"

#include "common/aov_ids.glsl"
#include "core/error.h"

namespace glimmer {

const std::vector<AovInfo>& aovTable() {
    static const std::vector<AovInfo> table = {
        {"final", VIEW_FINAL, "tone-mapped colour (PNG) or linear radiance (EXR)"},
        {"albedo", VIEW_ALBEDO, "base colour"},
        {"normal", VIEW_NORMAL, "world-space shading normal"},
        {"depth", VIEW_DEPTH, "distance from the camera (m; PNG and window: log2(1 + d) / 8)"},
        {"uv", VIEW_UV, "UV0 (32-bit)"},
        {"duvdx", VIEW_DUVDX, "UV derivative along screen x"},
        {"duvdy", VIEW_DUVDY, "UV derivative along screen y"},
        {"glint", VIEW_GLINT, "the NDF term D of the first light alone (linear)"},
        {"footprint", VIEW_FOOTPRINT, "footprint: R anisotropy ratio, G LOD, B/A method-specific (PNG and window: R log2(ratio)/4, G (LOD+16)/16)"},
        {"tangent", VIEW_TANGENT, "world-space tangent; a: the bitangent's sign (b = a cross(n, t))"},
        {"material", VIEW_ROUGHNESS_METALLIC, "R alpha, G metallic, B material id"},
        {"extra", VIEW_EXTRA, "method-specific debug channel (see the method's documentation)"},
        {"ao", VIEW_AO, "ambient occlusion: visibility of the environment term (GTAO x sky visibility, before multi-bounce)"},
        {"shadow", VIEW_SHADOW, "visibility of the first light, 0..1 (shadow maps; 0 where the surface faces away from it)"},
        {"clearcoat", VIEW_CLEARCOAT, "KHR_materials_clearcoat: R intensity c, G perceptual roughness, B the coat's share c Fc"},
        {"glintscale", VIEW_EXTRA, "wang2020: scale used per pixel, red micro, green meso, blue macro (= its extra view)"},
    };
    return table;
}

const AovInfo& findAov(const std::string& name) {
    for (const AovInfo& aov : aovTable())
        if (aov.name == name) return aov;
    std::string known;
    for (const AovInfo& aov : aovTable()) known += (known.empty() ? "" : ", ") + aov.name;
    throw UsageError("--aov: unknown output '" + name + "' (known: " + known + ")");
}

const AovInfo& nextDebugView(int viewId, int step) {
    std::vector<const AovInfo*> stops;
    for (const AovInfo& aov : aovTable()) {
        bool alias = false;
        for (const AovInfo* stop : stops) alias |= stop->viewId == aov.viewId;
        if (!alias) stops.push_back(&aov);
    }
    int n = int(stops.size()), current = 0;
    for (int i = 0; i < n; ++i)
        if (stops[size_t(i)]->viewId == viewId) current = i;
    return *stops[size_t(((current + step) % n + n) % n)];
}

}  // namespace glimmer
