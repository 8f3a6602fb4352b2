// The deferred renderer: one ordered list of passes (the frame list, docs/renderer.md) and one way to render a view
// with it, renderView(). Each pass lives in its feature folder (render/frame, shadows, ao, probes, image, forward),
// declares the frame resources it reads and writes (render/frame/frame_resources.h) and plugs in with one line of
// buildFrameList(); the glint method adds its own passes through its table entry. The scene is uploaded separately
// (GpuScene).
#pragma once
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "environment/environment.h"
#include "gl/handles.h"
#include "render/frame/frame_resources.h"
#include "render/frame/method_output_check.h"
#include "render/frame/pass.h"
#include "render/frame/pass_timer.h"
#include "render/gpu_scene.h"
#include "render/settings.h"
#include "render/view.h"
#include "scene/scene.h"

namespace glimmer {

class AmbientOcclusion;
class LightingPass;
class ProbesPass;
class ReflectionProbes;
class RendererCapture;
class ShadowMaps;
class TaaPass;
class ExposurePass;
class TonemapPass;

// Which passes a renderer's frame list holds.
enum class FrameKind {
    Full,     // every pass: shadows, G-buffer, AO, lighting, the method's passes, forward, TAA, post, tone mapping
    // The G-buffer and lighting of the default method, with the passes they read (run or not by the settings): what
    // a reflection probe's face sees (render/probes/reflection_probes.h). No forward or image passes.
    Capture,
};

class Renderer {
public:
    // Builds every program; throws gl::ShaderError with file:line on compile errors. A renderer made for another
    // renderer's views (probe captures) shares that renderer's environment instead of preparing its own.
    Renderer(std::filesystem::path shaderRoot, const RenderSettings& settings, FrameKind kind = FrameKind::Full,
             Environment* sharedEnvironment = nullptr);
    // A second full view of `source`'s scene (the window's split screen): it reads source's environment and
    // reflection probes, which source prepares (source renders first in each frame), instead of building and
    // capturing its own; it keeps them alive while it lives.
    Renderer(std::filesystem::path shaderRoot, const RenderSettings& settings, Renderer& source);
    ~Renderer();

    // Switches method or parameters. Rebuilds the lighting program when the method changes.
    void setSettings(const RenderSettings& settings);
    const RenderSettings& settings() const { return settings_; }
    // Rebuilds every program from disk; on failure keeps the previous ones and rethrows.
    void reloadPrograms();
    const std::filesystem::path& shaderRoot() const { return shaderRoot_; }
    std::vector<std::filesystem::path> shaderDependencies() const;

    // Hot reload: rebuilds only the programs built from one of `changedFiles` (canonical paths, as
    // shaderDependencies() lists them). Each program is swapped only after it compiled and linked; a failing one
    // keeps running its last good version and its error ("file:line: message") stays in shaderErrors() until a
    // later rebuild of that program succeeds. Returns the names of the programs rebuilt successfully.
    std::vector<std::string> reloadChangedPrograms(const std::vector<std::filesystem::path>& changedFiles);
    // Program name -> first error of its last failed rebuild (empty when every program is up to date).
    const std::map<std::string, std::string>& shaderErrors() const { return shaderErrors_; }

    // Window mode: when enabled and a view is rendered without measurePasses, each pass is wrapped in a
    // GL_TIME_ELAPSED query that is read back PassTimer::kFrames frames later only if its result is already
    // available: no glFinish, no stall. passTimings() then holds gpuMs (wallMs 0) of a frame a few frames old.
    // Meaningless on software renderers (llvmpipe times the submit, not the work).
    void setAsyncGpuTimers(bool enabled) { asyncGpuTimers_ = enabled; }
    // Called with each pass's name before its prepare(), where the on-demand work runs (probe captures, the sky
    // bake, method tables): the window's loading frame names the step in progress. Empty (the default): none.
    void setPrepareListener(std::function<void(const std::string& passName)> listener) {
        prepareListener_ = std::move(listener);
    }
    // How on-demand work that only refines the image and has not run yet (PrepareContext::refinements: the
    // environment's prefiltered maps, the reflection probes, the environment glints) is paced. AllAtOnce, the
    // default: every frame runs all of it (offscreen renders and tests see every term in their first frame).
    // Deferred: none runs (the window's first picture: the environment is a quick preview, see
    // Environment::update). OnePerFrame: each frame runs at most one (the window after its first picture).
    enum class RefinementPace { AllAtOnce, Deferred, OnePerFrame };
    void setRefinementPace(RefinementPace pace) { refinementPace_ = pace; }
    // What the last prepared frame left waiting (empty once the image is complete).
    const std::vector<std::string>& waitingRefinements() const { return waitingRefinements_; }

    // Renders one view: the environment for the scene, every pass's prepare() in list order (shadow fitting, probe
    // captures, the sky bake, the method's data, TAA's jitter...), the frame's uniforms, then every pass that runs.
    // `view` comes back with what the passes decided (jitter, post size). With measurePasses each pass is closed by
    // glFinish and timed (adds sync points; off in the window).
    void renderView(const Scene& scene, const GpuScene& gpuScene, View& view, bool measurePasses = false);
    // One frame of an unaccumulated view of camera at width x height (tests, probes' faces).
    void renderView(const Scene& scene, const GpuScene& gpuScene, const Camera& camera, int width, int height,
                    bool measurePasses = false);
    // Accumulating IBL modes (IblMode::accumulates) are Monte Carlo estimators: the view's `samples` estimates
    // averaged into one image (sample 0 renders the G-buffer, later ones reuse it; progress on stderr for long runs).
    // Other modes render one frame. measurePasses times the last sample's passes.
    void renderAccumulated(const Scene& scene, const GpuScene& gpuScene, View& view, int samples,
                           bool measurePasses = false);
    bool accumulating() const;

    // The last view rendered (with its jitter and post size) and whether TAA upsampled it.
    const View& lastView() const { return lastView_; }
    bool upsampled() const { return lastView_.postWidth != lastView_.width || lastView_.postHeight != lastView_.height; }
    const std::vector<PassTiming>& passTimings() const { return timer_.timings(); }
    // The on-demand passes of the last frame that ran any (method / IBL-mode data rebuilt after an edit, probe
    // captures; wall ms), kept until the next edit so the window can show them.
    const std::vector<PassTiming>& lastEditPasses() const { return editPasses_; }
    // An edit begins: lastEditPasses() then holds only what a later frame runs on demand (none when the edit needs
    // no such work), not the passes of an earlier frame (the start's, or the frame after the first picture's).
    void forgetEditPasses() { editPasses_.clear(); }

    // The frame list: each pass's name and declared resources, in order (tests walk it; checkFrameList()).
    std::vector<DeclaredPass> frameList() const;

    // Makes Scene::environment the active environment (built on first use, rebuilt when it changes); renderView
    // calls it too. `flag` names the spec's origin in error messages. A renderer with a shared environment leaves it.
    void prepareEnvironment(const Scene& scene, const std::string& flag = "scene environment");
    const Environment& environment() const { return *environment_; }
    // Reflection probes (captured on the frames where what they see changed; render/probes/reflection_probes.h).
    const ReflectionProbes& probes() const;
    const AmbientOcclusion& ambientOcclusion() const { return *ambientOcclusion_; }
    // The shadow maps of the last frame: views in use and what the shadow passes rendered (--stats, tests).
    const ShadowMaps& shadowMaps() const { return *shadowMaps_; }
    // What the glint method produced since the last reset (render/frame/method_output_check.h): read() waits for the GPU.
    MethodOutputCheck& methodOutput() { return methodOutput_; }

    // The frame's resources as the last view left them (tests read G-buffer targets, the glint part...).
    const FrameResources& resources() const { return resources_; }
    // Readbacks, bottom row first (GL order): radiance and display at the post size, depth at the render size.
    std::vector<float> readHdr() const;        // RGBA32F
    std::vector<uint8_t> readDisplay() const;  // RGBA8, tone-mapped sRGB
    std::vector<float> readDepth() const;      // reversed Z
    // The method's lighting target `index` of the last frame (GlintMethod::lightingTargets; empty without), RGBA32F.
    std::vector<float> readMethodTarget(size_t index) const;
    GLuint displayTexture() const { return resources_.get(FrameResource::Display).texture(); }
    GLuint displayFramebuffer() const;
    uint32_t frameIndex() const { return frameIndex_; }

    // The image pipeline (docs/image.md). Auto exposure moves towards each frame's metered value with this
    // weight (1: at once, the offscreen default; the window passes 1 - exp(-dt / time constant)).
    void setExposureAdaptation(float weight);
    float meteredExposureEv() const;
    // TAA: frames accumulated since the last history reset, the resets so far, a reset.
    unsigned taaFrames() const;
    unsigned taaResets() const;
    void resetHistory();

private:
    void initialise();   // what every constructor does once the environment is chosen
    // The frame list, in order (every pass of FrameKind, then the method's passes after lighting). Builds all
    // first, then swaps: a failure leaves the previous list in place.
    void buildFrameList();
    std::vector<std::unique_ptr<Pass>> methodPasses() const;
    std::vector<gl::Program*> programs() const;
    // Everything a pass reads while it executes, for one view, in one place.
    FrameContext frameContext(const Scene& scene, const GpuScene& gpuScene, const View& view, bool blendSample,
                              const glm::mat4& viewProjection);
    void uploadFrameUniforms(const Scene& scene, const GpuScene& gpuScene, const View& view,
                             const glm::mat4& projection);
    void recordOnDemand(const std::string& name, double ms, bool measurePasses);
    RefinementBudget refinementBudget() const;   // this frame's, from refinementPace_
    void prepareEnvironment(const Scene& scene, const std::string& flag, RefinementBudget& budget,
                            const std::function<void(const std::string&, double)>& recordOnDemand);

    std::filesystem::path shaderRoot_;
    RenderSettings settings_;
    FrameKind kind_;
    std::shared_ptr<Environment> ownEnvironment_;        // null when the environment is another renderer's
    std::shared_ptr<Environment> borrowedEnvironment_;   // source's, for a second view (keeps it alive)
    Environment* environment_;
    // The reflection probes: this renderer's (invalidated by every buildFrameList: rebuilt shaders capture again),
    // or source's for a second view, which never updates them (probesBorrowed_).
    std::shared_ptr<ReflectionProbes> probes_;
    bool probesBorrowed_ = false;
    // Feature state shared by the passes of one feature folder.
    std::shared_ptr<ShadowMaps> shadowMaps_;
    std::shared_ptr<AmbientOcclusion> ambientOcclusion_;
    std::unique_ptr<RendererCapture> capture_;   // how IBL modes render the scene (per-object maps)
    // The frame list, and the passes the renderer itself talks to (settings, readbacks): never one pass to another.
    std::vector<std::unique_ptr<Pass>> frame_;
    LightingPass* lighting_ = nullptr;
    ProbesPass* probesPass_ = nullptr;
    TaaPass* taa_ = nullptr;
    ExposurePass* exposure_ = nullptr;
    TonemapPass* tonemap_ = nullptr;
    FrameResources resources_;
    bool resized_ = false;   // every pass of the list has been resized to lastView_'s render size
    View lastView_;
    gl::Buffer frameUniforms_;
    MethodOutputCheck methodOutput_;   // bound with the frame uniforms, read by the lighting pass
    gl::VertexArray emptyVao_;
    PassTimer timer_;
    std::vector<PassTiming> editPasses_;
    bool editPassesOfThisFrame_ = false;   // editPasses_ already holds on-demand passes of the current frame
    std::map<std::string, std::string> shaderErrors_;
    bool asyncGpuTimers_ = false;
    std::function<void(const std::string&)> prepareListener_;
    RefinementPace refinementPace_ = RefinementPace::AllAtOnce;
    std::vector<std::string> waitingRefinements_;
    uint32_t frameIndex_ = 0;
};

}  // namespace glimmer
