// C++ mirrors of the GPU blocks declared in shaders/common/frame.glsl. Layouts must match (std140 / std430).
#pragma once
#include "common/bindings.glsl"
#include <glm/glm.hpp>

namespace glimmer {

struct FrameUniforms {          // std140, binding 0
    glm::mat4 view;
    glm::mat4 projection;
    glm::mat4 viewProjection;
    glm::mat4 inverseViewProjection;
    glm::vec4 cameraPosition;
    glm::vec4 skyColor;
    glm::ivec4 viewport;        // width, height, frame index, debug view
    glm::vec4 exposure;         // exposure multiplier, light count, ambient scale, area lights (the last ones)
    glm::uvec4 sample;          // accumulation sample index, unused x3 (see Renderer::setSampleIndex)
    glm::vec4 jitter;           // TAA jitter in pixels (xy), glints at the unjittered centre (z = 1), unused
};
static_assert(sizeof(FrameUniforms) == 4 * 64 + 6 * 16);

struct GpuLight {               // std430, binding 1 (fields: shaders/common/frame.glsl)
    glm::vec4 vectorType;
    glm::vec4 colorIntensity;
    glm::vec4 spotAxisScale;
    glm::vec4 spotOffsetRange;
    glm::vec4 areaU;
    glm::vec4 areaV;
};
static_assert(sizeof(GpuLight) == 6 * 16);

struct GpuMaterial {            // std430, binding 2
    glm::vec4 baseColor;
    glm::vec4 alphaMetallicNdfGlinty;
    glm::vec4 densityCutoff;    // x density scale, y alpha cutoff, z clear coat, w clear coat roughness
};

// Binding points (uniform blocks and storage buffers).
constexpr unsigned kFrameBinding = BINDING_FRAME;
constexpr unsigned kLightBinding = BINDING_LIGHTS;
constexpr unsigned kMaterialBinding = BINDING_MATERIALS;
constexpr unsigned kMethodParamBinding = BINDING_METHOD_PARAMS;

}  // namespace glimmer
