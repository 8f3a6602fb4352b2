// One pass of the frame. The renderer holds one ordered list of passes (Renderer's frame list, docs/renderer.md)
// and walks it for everything: resize(), prepare(), execute(), the programs to hot reload, and the tests. A pass
// owns its programs and private targets, declares the frame resources it reads and writes (resources(); checked:
// render/frame/frame_resources.h), sets its complete pipeline state (gl/pipeline_state.h) before it draws, and
// reaches other passes' outputs only through the resource table. The renderer wraps execute() in the pass's debug
// group and timer (PassScope) named name().
#pragma once
#include <glad/gl.h>

#include <functional>
#include <string>
#include <vector>

#include "environment/environment.h"
#include "environment/ibl/ibl_modes.h"
#include "gl/program.h"
#include "glints/methods.h"
#include "render/frame/frame_resources.h"
#include "render/gpu_scene.h"
#include "render/settings.h"
#include "render/view.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace glimmer {

// How many refinements (see PrepareContext::refinements) one frame may run: take() says whether `what` may run
// now; what has to wait is listed, so the window can say what is still being refined.
class RefinementBudget {
public:
    static constexpr int kUnlimited = -1;
    explicit RefinementBudget(int allowed = kUnlimited) : left_(allowed) {}
    bool take(const std::string& what) {
        if (left_ == 0) {
            waiting_.push_back(what);
            return false;
        }
        if (left_ > 0) --left_;
        return true;
    }
    // Work that could not run for another reason (it needs a refinement that is still waiting).
    void wait(const std::string& what) { waiting_.push_back(what); }
    const std::vector<std::string>& waiting() const { return waiting_; }

private:
    int left_;
    std::vector<std::string> waiting_;
};

// What prepare() sees: the view (which a pass may change: TAA sets its jitter), the scene, the settings, the
// environment, and where work done here reports its time: recordStats lists it in --stats only (the sky bake),
// recordOnDemand also in the window's "last edit" line (data rebuilt after an edit: probes, method tables).
struct PrepareContext {
    const Scene& scene;
    const GpuScene& gpuScene;
    View& view;
    const RenderSettings& settings;
    Environment& environment;
    FrameResources& resources;
    // A later sample k > 0 of an accumulating IBL mode (the G-buffer of sample 0 is reused).
    bool blendSample = false;
    // Work that only refines the image and is not there yet (the environment's prefiltered maps, the reflection
    // probes, the environment glints) asks this budget first: the window's first picture takes none, later frames one
    // each, so the player sees the scene sooner and never waits on all of them at once (Renderer::setRefinementPace).
    RefinementBudget& refinements;
    std::function<void(const std::string& name, double wallMs)> recordStats, recordOnDemand;
};

// Everything a pass may read while it executes. Built once per view by frameContext() (render/renderer.cpp).
struct FrameContext {
    const Scene& scene;
    const GpuScene& gpuScene;
    const View& view;
    const Camera& camera;
    const RenderSettings& settings;
    FrameResources& resources;
    Environment& environment;
    int width, height;            // render size
    int postWidth, postHeight;    // the post passes' size (TAA upsampling resolves to the output size)
    // A later sample k > 0 of an accumulating IBL mode: the G-buffer of sample 0 is reused and the radiance is
    // blended into the running mean with weight blendWeight = 1 / (k + 1) (1 otherwise).
    bool blendSample;
    float blendWeight;
    GLuint emptyVao;              // for full-screen triangles
    glm::mat4 viewProjection;     // of this frame (geometry passes cull against it; jittered with TAA)
    bool temporalAa;              // this frame is jittered and resolved by TAA (aa=taa)
};

// The level of detail of this frame's opaque geometry (lod.pixel_error pixels of error at the render height):
// the G-buffer and every pass that depth-tests against it draw the same one.
inline LodView geometryLod(const FrameContext& frame) {
    return lodViewFor(frame.camera, frame.height, frame.settings.value(param::lod_pixel_error));
}

class Pass {
public:
    virtual ~Pass() = default;
    virtual const char* name() const = 0;
    // The frame resources this pass reads and writes (render/frame/frame_resources.h).
    virtual PassResources resources() const = 0;
    virtual std::vector<gl::Program*> programs() = 0;
    // When the view's render or post size changed: (re)allocates the targets the pass owns and publishes them.
    virtual void resize(const View& view, FrameResources& resources) {}
    // Once per view, before any pass executes and before the frame's uniforms are set: per-frame set-up and
    // on-demand work (shadow fitting, the sky-visibility bake, TAA's jitter, probe captures, the method's and IBL
    // mode's data). May render other views (probes, per-object maps).
    virtual void prepare(PrepareContext& context) {}
    virtual bool runs(const FrameContext& frame) const { return true; }
    virtual void execute(const FrameContext& frame) = 0;
};

}  // namespace glimmer
