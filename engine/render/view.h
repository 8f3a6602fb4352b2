// A view of the scene: what one renderView() call renders (render/renderer.h). Every image the engine makes is a
// view: the window's frame and its split side, an offscreen render, a reflection probe's cube face, an IBL mode's
// per-object map, the AOVs a CPU reference reads.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "scene/camera.h"

namespace glimmer {

struct View {
    Camera camera;
    int width = 1, height = 1;               // render size
    int outputWidth = 0, outputHeight = 0;   // display size (0 x 0: the render size); TAA may upsample to it
    // Accumulating IBL modes (IblMode::accumulates): sample k of this view. k > 0 reuses sample 0's G-buffer and
    // blends into the running mean with weight 1 / (k + 1), so scene, camera, size and settings must be sample 0's.
    uint32_t sampleIndex = 0;

    // Set while the view renders (renderView resets them, the TAA pass's prepare() sets them when TAA runs):
    bool temporalAa = false;                 // jittered and resolved by TAA (aa=taa)
    glm::vec2 jitter{0.0f};                  // this frame's sub-pixel offset in render pixels (0: unjittered)
    int postWidth = 0, postHeight = 0;       // the post passes' size: the render size, or the output size (TAAU)

    float aspect() const { return float(width) / float(height); }
};

}  // namespace glimmer
