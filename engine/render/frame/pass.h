// One pass of the frame (render/renderer.cpp lists them in order): it owns its programs, reads and writes the
// targets named in its header, sets its complete pipeline state (gl/pipeline_state.h) and draws. The renderer
// wraps execute() in the pass's debug group and timer (PassScope) named name().
#pragma once
#include <glad/gl.h>

#include <vector>

#include "gl/program.h"
#include "glints/methods.h"
#include "environment/ibl/ibl_modes.h"
#include "environment/environment.h"
#include "render/frame/gbuffer.h"
#include "render/gpu_scene.h"
#include "render/settings.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace glimmer {

class ReflectionProbes;
class ShadowMaps;

// Everything a pass may read in one frame. The frame's uniform blocks (frame, method and IBL parameters) are
// bound before the first pass (shaders/common/bindings.glsl).
struct FrameContext {
    const Scene& scene;
    const GpuScene& gpuScene;
    const Camera& camera;
    const RenderSettings& settings;
    FrameTargets& targets;
    Environment& environment;
    GlintMethodResources* methodResources;   // null when the method has none
    IblModeResources* iblResources;          // null when the IBL mode has none
    int width, height;
    // A later sample k > 0 of an accumulating IBL mode: the G-buffer of sample 0 is reused and the radiance is
    // blended into the running mean with weight blendWeight = 1 / (k + 1) (1 otherwise).
    bool blendSample;
    float blendWeight;
    GLuint emptyVao;                         // for full-screen triangles
    glm::mat4 viewProjection;                // of this frame (geometry passes cull against it; jittered with TAA)
    // TAA (docs/image.md): this frame is jittered and resolved; the lighting pass writes the glint part.
    bool temporalAa = false;
    // Reflection probes bound by the lighting pass; probesActive false (probe captures, IBL modes that do not
    // read probes, probes.enabled = 0) binds none, so the distant environment alone lights the frame.
    const ReflectionProbes* probes = nullptr;
    bool probesActive = false;
    GLuint ambientOcclusion = 0;             // factor on the environment term (AmbientOcclusion::occlusionTexture)
    ShadowMaps* shadows = nullptr;           // the lights' shadow maps, fitted for this frame (render/shadows/shadow_maps.h)
};

// The level of detail of this frame's opaque geometry (lod.pixel_error pixels of error at the render height):
// the G-buffer and every pass that depth-tests against it draw the same one.
inline LodView geometryLod(const FrameContext& frame) {
    return lodViewFor(frame.camera, frame.height, frame.settings.common_("lod.pixel_error"));
}

class Pass {
public:
    virtual ~Pass() = default;
    virtual const char* name() const = 0;
    virtual std::vector<gl::Program*> programs() = 0;
    virtual bool runs(const FrameContext& frame) const { return true; }
    virtual void execute(const FrameContext& frame) = 0;
};

}  // namespace glimmer
