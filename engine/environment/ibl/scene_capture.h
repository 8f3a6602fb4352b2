// How an IBL mode renders the scene (the per-object environment maps of the regular-sampling paper, Sec. 3)
// without the ibl folder depending on the renderer: the renderer hands an implementation to
// IblModeResources::prepare (render/renderer_capture.h).
#pragma once
#include <vector>

#include "scene/camera.h"
#include "scene/scene.h"

namespace glimmer::ibl {

class SceneCapture {
public:
    virtual ~SceneCapture() = default;
    // The HDR radiance (RGBA32F, bottom row first) of `scene` seen by each camera at size x size, rendered with
    // the default settings (prefiltered environment, smooth method).
    virtual std::vector<std::vector<float>> renderHdr(const Scene& scene, const std::vector<Camera>& cameras,
                                                      int size) = 0;
};

}  // namespace glimmer::ibl
