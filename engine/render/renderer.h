// The deferred renderer: a fixed list of passes (render/passes/): G-buffer, lighting (with the selected glint
// method and IBL mode), the method's own passes (GlintMethod::createPasses), the image pipeline (TAA, auto exposure,
// bloom; docs/image.md), tone mapping. Owns the passes and the frame targets; the scene is uploaded separately
// (GpuScene).
#pragma once
#include <array>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "glints/methods.h"
#include "environment/ibl/ibl_modes.h"
#include "environment/environment.h"
#include "render/frame/gbuffer.h"
#include "render/gpu_scene.h"
#include "render/frame/pass.h"
#include "render/frame/pass_timer.h"
#include "render/lights/ltc_texture.h"
#include "render/probes/reflection_probes.h"
#include "environment/environment_glints.h"
#include "render/settings.h"
#include "scene/scene.h"

namespace glimmer {

class GBufferPass;
class GtaoPass;
class AoResolvePass;
class ShadowMaskPass;
class AmbientOcclusion;
class LightingPass;
class TaaPass;
class ExposurePass;
class BloomPass;
class ShadowMapPass;
class ShadowMaps;
class TonemapPass;
class ForwardTarget;
class RendererCapture;

class Renderer {
public:
    // Builds every program; throws gl::ShaderError with file:line on compile errors.
    Renderer(std::filesystem::path shaderRoot, const RenderSettings& settings);
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

    // Window mode: when enabled and render() is called without measurePasses, each pass is wrapped in a
    // GL_TIME_ELAPSED query that is read back PassTimer::kFrames frames later only if its result is already
    // available: no glFinish, no stall. passTimings() then holds gpuMs (wallMs 0) of a frame a few frames old.
    // Meaningless on software renderers (llvmpipe times the submit, not the work).
    void setAsyncGpuTimers(bool enabled) { asyncGpuTimers_ = enabled; }

    // Accumulation for IBL modes that are Monte Carlo estimators (IblMode::accumulates). Sample index 0 starts a
    // new mean; index k > 0 blends the new estimate into the HDR target with weight 1 / (k + 1) and skips the
    // G-buffer pass, so the caller promises that scene, camera, size and settings are those of sample 0.
    // Ignored (always a fresh frame) for deterministic modes.
    void setSampleIndex(uint32_t index) { sampleIndex_ = index; }
    bool accumulating() const { return findIblMode(settings_.ibl).accumulates; }

    // Renders one frame into the targets (HDR radiance or the debug view, then the display image).
    // With measurePasses, each pass is closed by glFinish and timed (adds sync points; off in the window).
    void render(const Scene& scene, const GpuScene& gpuScene, const Camera& camera, int width, int height,
                bool measurePasses = false);
    // The size the frame is displayed at (0 x 0: the render size). With aa=taa and a render size below it, the TAA
    // pass resolves to this size (TAA upsampling) and the post passes and the display image have it; otherwise
    // they have the render size and the caller upscales (render/image/upscale.h). targets().postWidth() tells which.
    void setOutputSize(int width, int height) { outputWidth_ = width, outputHeight_ = height; }
    // Whether the last frame was upsampled by TAA.
    bool upsampled() const { return targets_.postWidth() != targets_.width() || targets_.postHeight() != targets_.height(); }
    const std::vector<PassTiming>& passTimings() const { return timer_.timings(); }
    // The on-demand passes of the last frame that ran any (method / IBL-mode data rebuilt after an edit, wall ms),
    // kept until the next edit so the window can show them.
    const std::vector<PassTiming>& lastEditPasses() const { return editPasses_; }

    // Makes Scene::environment the active environment (built on first use, rebuilt when it changes); render()
    // calls it too. `flag` names the spec's origin in error messages.
    void prepareEnvironment(const Scene& scene, const std::string& flag = "scene environment");
    const Environment& environment() const { return environment_; }
    // Reflection probes (captured on the frames where what they see changed; render/probes/reflection_probes.h).
    const ReflectionProbes& probes() const { return *probes_; }
    const AmbientOcclusion& ambientOcclusion() const { return *ambientOcclusion_; }

    const FrameTargets& targets() const { return targets_; }
    // Readbacks, bottom row first (GL order), at the post size (targets().postWidth() x postHeight()).
    std::vector<float> readHdr() const;        // RGBA32F
    std::vector<uint8_t> readDisplay() const;  // RGBA8, tone-mapped sRGB
    // The method passes' inputs of the last frame (methods with GlintMethod::glintPostPass, else empty): the
    // environment-glint and light-glint targets, RGBA32F bottom-up (layout in FrameTargets).
    std::vector<float> readGlintEnvironment() const;
    std::vector<float> readGlintLights() const;
    uint32_t frameIndex() const { return frameIndex_; }
    // The shadow maps of the last frame: views in use and what the shadow passes rendered (--stats, tests).
    const ShadowMaps& shadowMaps() const { return *shadowMaps_; }

    // The image pipeline (docs/image.md). Auto exposure moves towards each frame's metered value with this
    // weight (1: at once, the offscreen default; the window passes 1 - exp(-dt / time constant)).
    void setExposureAdaptation(float weight);
    float meteredExposureEv() const;
    // TAA: frames accumulated since the last history reset, the jitter of the last frame (pixels), a reset.
    unsigned taaFrames() const;
    unsigned taaResets() const;
    glm::vec2 lastJitter() const { return lastJitter_; }
    void resetHistory();

private:
    void buildPasses();          // every pass and the method's resources; throws, keeping the previous ones
    void createMethodResources();
    // On-demand data of the glint method and the IBL mode (tables, trees, the prefiltered environment of
    // wang2020), rebuilt between the G-buffer and the lighting pass; the passes that ran are listed in --stats.
    void updateMethodData(bool measurePasses);
    void uploadMethodParams(const Scene& scene);
    void runPass(Pass& pass, const FrameContext& frame);
    // The frame, in order (programs() and render() walk this list).
    std::vector<Pass*> frame() const;
    std::vector<gl::Program*> programs() const;

    std::filesystem::path shaderRoot_;
    RenderSettings settings_;
    std::unique_ptr<ShadowMaps> shadowMaps_;
    std::unique_ptr<ShadowMapPass> sunShadowPass_, pointShadowPass_;
    std::unique_ptr<GBufferPass> gbufferPass_;
    std::unique_ptr<AmbientOcclusion> ambientOcclusion_;   // targets and baked sky visibility of the AO passes
    std::unique_ptr<GtaoPass> gtaoPass_;
    std::unique_ptr<AoResolvePass> aoResolvePass_;
    std::unique_ptr<ShadowMaskPass> shadowMaskPass_;
    std::unique_ptr<LightingPass> lightingPass_;
    std::vector<std::unique_ptr<Pass>> methodPasses_;
    std::unique_ptr<TaaPass> taaPass_;
    std::unique_ptr<ExposurePass> exposurePass_;
    std::unique_ptr<BloomPass> bloomPass_;
    std::unique_ptr<TonemapPass> tonemapPass_;
    glm::vec2 lastJitter_{0.0f};
    // After lighting: emission and alpha-blended surfaces (render/forward/forward_target.h), sharing one target.
    std::shared_ptr<ForwardTarget> forwardTarget_;
    std::unique_ptr<Pass> forwardRestorePass_, forwardSavePass_, emissivePass_, transparentPass_;
    std::unique_ptr<GlintMethodResources> methodResources_;
    std::string methodResourcesFrom_;   // GlintMethod::resourcesFrom of the resources made (user methods' headers may change it)
    std::unique_ptr<IblModeResources> iblResources_;
    std::unique_ptr<RendererCapture> capture_;   // how IBL modes render the scene (per-object maps)
    std::unique_ptr<ReflectionProbes> probes_;
    Environment environment_;
    LtcTexture ltcTable_;   // the area lights' LTC tables, bound for every frame (render/lights/)
    EnvironmentGlints environmentGlints_;   // Kneiphof & Klein 2025's levels for methods with environment glints
    FrameTargets targets_;
    gl::Buffer frameUniforms_, methodParams_, iblParams_;
    gl::Buffer materialMethodParams_;   // per-material method parameters (BINDING_MATERIAL_METHOD_PARAMS)
    long long materialMethodParamsBytes_ = 0;
    ParamValues sharedMethodValues_;    // what the method's shared GPU data are built from (glint_mapping.h)
    uint32_t sampleIndex_ = 0;
    gl::VertexArray emptyVao_;
    PassTimer timer_;
    std::vector<PassTiming> editPasses_;
    bool editPassesOfThisFrame_ = false;   // editPasses_ already holds on-demand passes of the current frame
    void recordOnDemand(const std::string& name, double ms, bool measurePasses);
    std::map<std::string, std::string> shaderErrors_;
    bool asyncGpuTimers_ = false;
    uint32_t frameIndex_ = 0;
    int outputWidth_ = 0, outputHeight_ = 0;
};

}  // namespace glimmer
