#include "render/aov.h"

#include "core/error.h"

namespace glimmer {

const std::vector<AovInfo>& aovTable() {
    static const std::vector<AovInfo> table = {
        {"final", 0, "tone-mapped colour (PNG) or linear radiance (EXR)"},
        {"albedo", 1, "base colour"},
        {"normal", 2, "world-space shading normal"},
        {"depth", 3, "distance from the camera (m)"},
        {"uv", 4, "UV0 (32-bit)"},
        {"duvdx", 5, "UV derivative along screen x"},
        {"duvdy", 6, "UV derivative along screen y"},
        {"glint", 7, "the NDF term D of the first light alone (linear)"},
        {"footprint", 8, "footprint: R anisotropy ratio, G LOD, B/A method-specific"},
        {"tangent", 9, "world-space tangent; a: the bitangent's sign (b = a cross(n, t))"},
        {"material", 10, "R alpha, G metallic, B material id"},
        {"extra", 11, "method-specific debug channel (see the method's documentation)"},
        {"ao", 13, "ambient occlusion: visibility of the environment term (GTAO x sky visibility, before multi-bounce)"},
        {"shadow", 12, "visibility of the first light, 0..1 (shadow maps; 0 where the surface faces away from it)"},
        {"clearcoat", 14, "KHR_materials_clearcoat: R intensity c, G perceptual roughness, B the coat's share c Fc"},
        {"glintscale", 11, "wang2020: scale used per pixel, red micro, green meso, blue macro (= its extra view)"},
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

}  // namespace glimmer
