#include "render/renderer.h"

#include <algorithm>
#include <cmath>

#include "common/bindings.glsl"
#include "core/clock.h"
#include "core/error.h"
#include "core/log.h"
#include "gl/debug.h"
#include "glints/methods.h"
#include "render/ao/ambient_occlusion.h"
#include "render/ao/ao_resolve_pass.h"
#include "render/ao/gtao_pass.h"
#include "render/forward/emissive_pass.h"
#include "render/forward/forward_target.h"
#include "render/forward/transparent_pass.h"
#include "render/frame/environment_glints_pass.h"
#include "render/frame/gbuffer_pass.h"
#include "render/frame/lighting_pass.h"
#include "render/frame/method_pass_host.h"
#include "render/image/bloom_pass.h"
#include "render/image/exposure_pass.h"
#include "render/image/halton_jitter.h"
#include "render/image/taa_pass.h"
#include "render/image/tonemap_pass.h"
#include "render/probes/probes_pass.h"
#include "render/renderer_capture.h"
#include "render/shader_interface.h"
#include "render/shadows/shadow_map_pass.h"
#include "render/shadows/shadow_mask_pass.h"
#include "render/shadows/shadow_maps.h"

namespace glimmer {

Renderer::Renderer(std::filesystem::path shaderRoot, const RenderSettings& settings, FrameKind kind,
                   Environment* sharedEnvironment)
    : shaderRoot_(std::move(shaderRoot)), settings_(settings), kind_(kind) {
    gl::enableDebugOutput();
    if (!sharedEnvironment) ownEnvironment_ = std::make_shared<Environment>(shaderRoot_);
    environment_ = sharedEnvironment ? sharedEnvironment : ownEnvironment_.get();
    initialise();
}

Renderer::Renderer(std::filesystem::path shaderRoot, const RenderSettings& settings, Renderer& source)
    : shaderRoot_(std::move(shaderRoot)), settings_(settings), kind_(FrameKind::Full) {
    gl::enableDebugOutput();
    // The split screen's right side used to capture its own probes and prepare its own environment: a 4.8 s freeze
    // at the first B (issue 39). The same scene and common parameters give the same probes and maps.
    borrowedEnvironment_ = source.ownEnvironment_;
    environment_ = source.environment_;
    probes_ = source.probes_;
    probesBorrowed_ = true;
    initialise();
}

void Renderer::initialise() {
    frameUniforms_ = gl::createBuffer(sizeof(FrameUniforms), nullptr);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    emptyVao_ = gl::VertexArray(vao);
    capture_ = std::make_unique<RendererCapture>(shaderRoot_, environment_);
    ambientOcclusion_ = std::make_shared<AmbientOcclusion>();
    shadowMaps_ = std::make_shared<ShadowMaps>();
    methodOutput_.bind();   // also for probe captures before the first frame
    buildFrameList();
}

Renderer::~Renderer() = default;

std::vector<std::unique_ptr<Pass>> Renderer::methodPasses() const {
    std::vector<std::unique_ptr<Pass>> passes;
    const GlintMethod& method = findGlintMethod(settings_.method);
    if (method.createPasses)
        for (std::unique_ptr<MethodPass>& pass : method.createPasses(shaderRoot_))
            passes.push_back(std::make_unique<MethodPassHost>(std::move(pass)));
    return passes;
}

// The frame, in order. A new pass is one line here (and a folder for its class); the tests walk this list.
void Renderer::buildFrameList() {
    const std::filesystem::path& root = shaderRoot_;
    auto forward = std::make_shared<ForwardTarget>();
    std::vector<std::unique_ptr<Pass>> list;
    auto add = [&list](auto pass) {
        auto* raw = pass.get();
        list.push_back(std::move(pass));
        return raw;
    };
    add(std::make_unique<ShadowMapPass>(root, ShadowArray::Sun, shadowMaps_));    // its prepare() fits every view
    add(std::make_unique<ShadowMapPass>(root, ShadowArray::Local, shadowMaps_));
    if (!probes_) probes_ = std::make_shared<ReflectionProbes>(root);
    ProbesPass* probes = add(std::make_unique<ProbesPass>(probes_, !probesBorrowed_));   // captures on demand
    add(std::make_unique<EnvironmentGlintsPass>(root));   // environment glints' levels on demand (after the probes)
    add(std::make_unique<GBufferPass>(root));
    add(std::make_unique<GtaoPass>(root, ambientOcclusion_));                     // sky bake on demand
    add(std::make_unique<AoResolvePass>(root, ambientOcclusion_));
    add(std::make_unique<ShadowMaskPass>(root, shadowMaps_));
    if (kind_ == FrameKind::Full)   // accumulating IBL modes: the opaque mean without last sample's composite
        add(std::make_unique<ForwardAccumulationPass>(forward, ForwardAccumulationPass::Mode::Restore));
    LightingPass* lighting = add(std::make_unique<LightingPass>(root, settings_, *capture_));
    TaaPass* taa = nullptr;
    ExposurePass* exposure = nullptr;
    TonemapPass* tonemap = nullptr;
    if (kind_ == FrameKind::Full) {
        for (auto& pass : methodPasses()) add(std::move(pass));            // e.g. Wang et al. 2020 Sec. 4.4
        add(std::make_unique<ForwardAccumulationPass>(forward, ForwardAccumulationPass::Mode::Save));
        add(std::make_unique<EmissivePass>(root, forward));                // emission of opaque and masked surfaces
        add(std::make_unique<TransparentPass>(root, forward));             // glTF BLEND surfaces, back to front
        taa = add(std::make_unique<TaaPass>(root));                        // sets the view's jitter in prepare()
        exposure = add(std::make_unique<ExposurePass>(root));
        add(std::make_unique<BloomPass>(root));
        tonemap = add(std::make_unique<TonemapPass>(root));
    }
    frame_ = std::move(list);
    lighting_ = lighting, probesPass_ = probes, taa_ = taa, exposure_ = exposure, tonemap_ = tonemap;
    if (!probesBorrowed_) probes_->invalidate();   // rebuilt programs (F5) capture again, as a fresh renderer would
    shadowMaps_->invalidate();   // the maps were drawn by the previous depth program
    resized_ = false;            // the new passes own no targets yet
}

std::vector<DeclaredPass> Renderer::frameList() const {
    std::vector<DeclaredPass> list;
    for (const auto& pass : frame_) list.push_back({pass->name(), pass->resources()});
    return list;
}

void Renderer::reloadPrograms() {
    try {
        buildFrameList();
        shaderErrors_.clear();
    } catch (const std::exception& e) {
        shaderErrors_["all programs"] = e.what();
        throw;
    }
}

std::vector<gl::Program*> Renderer::programs() const {
    std::vector<gl::Program*> all;
    for (const auto& pass : frame_)
        for (gl::Program* program : pass->programs()) all.push_back(program);
    return all;
}

std::vector<std::string> Renderer::reloadChangedPrograms(const std::vector<std::filesystem::path>& changedFiles) {
    std::vector<std::string> rebuilt;
    for (gl::Program* program : programs()) {
        bool affected = false;
        for (const auto& file : changedFiles)
            affected |= std::find(program->dependencies().begin(), program->dependencies().end(), file) !=
                        program->dependencies().end();
        if (!affected) continue;
        const std::string name = program->desc().name;
        // The lighting program's description comes from the method table again: a user method's header may have
        // changed its parameters (P_<NAME> block) since it was built.
        const bool lighting = program == lighting_->programs().front();
        try {
            if (lighting) {
                lighting_->rebuildProgram();
            } else {
                gl::Program fresh(shaderRoot_, program->desc());
                *program = std::move(fresh);  // swap only after a successful link
            }
            if (name == "shadow_depth" || name == "shadow_depth_masked") shadowMaps_->invalidate();
            shaderErrors_.erase(name);
            shaderErrors_.erase("all programs");
            rebuilt.push_back(name);
        } catch (const std::exception& e) {
            shaderErrors_[name] = e.what();
        }
    }
    return rebuilt;
}

void Renderer::setSettings(const RenderSettings& settings) {
    const bool shadows = settings.value(param::shadow_enabled) > 0.5f;
    const bool methodChanged = settings.method != settings_.method || settings.ibl != settings_.ibl;
    // Any edit is a cut for TAA: the history shows the old image.
    if (taa_ && (methodChanged || settings.common != settings_.common || settings.methods != settings_.methods ||
                 settings.debugView != settings_.debugView || settings.iblValues != settings_.iblValues))
        taa_->reset();
    if (!methodChanged) {   // at most shadows toggled: only the lighting programs change
        if (shadows != lighting_->shadows()) lighting_->setShadows(shadows);
        settings_ = settings;
        return;
    }
    // The lighting pass (and, for a new method, the method's passes) of the new settings. Build first: a failure
    // keeps the previous method running.
    auto lighting = std::make_unique<LightingPass>(shaderRoot_, settings, *capture_);
    std::vector<std::unique_ptr<Pass>> passes;
    const std::string previousName = lighting_->programs().front()->desc().name;
    const RenderSettings previous = settings_;
    settings_ = settings;
    try {
        if (methodChanged && kind_ == FrameKind::Full) passes = methodPasses();
    } catch (...) {
        settings_ = previous;
        throw;
    }
    // Swap the lighting pass in place; replace the method's passes (those between lighting and forward_save).
    auto at = std::find_if(frame_.begin(), frame_.end(), [&](const auto& p) { return p.get() == lighting_; });
    *at = std::move(lighting);
    lighting_ = static_cast<LightingPass*>(at->get());
    if (methodChanged && kind_ == FrameKind::Full) {
        auto first = at + 1;
        auto last = std::find_if(first, frame_.end(), [](const auto& p) { return std::string(p->name()) == "forward_save"; });
        first = frame_.erase(first, last);
        frame_.insert(first, std::make_move_iterator(passes.begin()), std::make_move_iterator(passes.end()));
    }
    shaderErrors_.erase(previousName);
    resized_ = false;   // the new lighting pass owns no targets yet
    timer_.discard();   // the frames in flight timed the previous method's passes
}

std::vector<std::filesystem::path> Renderer::shaderDependencies() const {
    std::vector<std::filesystem::path> all;
    for (const gl::Program* p : programs())
        for (const auto& f : p->dependencies())
            if (std::find(all.begin(), all.end(), f) == all.end()) all.push_back(f);
    return all;
}

RefinementBudget Renderer::refinementBudget() const {
    switch (refinementPace_) {
        case RefinementPace::Deferred: return RefinementBudget(0);
        case RefinementPace::OnePerFrame: return RefinementBudget(1);
        case RefinementPace::AllAtOnce: break;
    }
    return RefinementBudget(RefinementBudget::kUnlimited);
}

void Renderer::prepareEnvironment(const Scene& scene, const std::string& flag) {
    RefinementBudget budget = refinementBudget();
    prepareEnvironment(scene, flag, budget, [](const std::string&, double) {});
    waitingRefinements_ = budget.waiting();
}

void Renderer::prepareEnvironment(const Scene& scene, const std::string& flag, RefinementBudget& budget,
                                  const std::function<void(const std::string&, double)>& recordOnDemand) {
    if (!ownEnvironment_) return;
    // Paced: a new environment missing from the disk cache comes as a preview first (Environment::update).
    ownEnvironment_->update(scene.environment, sunFromScene(scene), flag, refinementPace_ != RefinementPace::AllAtOnce);
    // Paced, one prefilter walk a frame (a few hundred ms each on llvmpipe rather than one freeze of seconds).
    if (!ownEnvironment_->refined() && budget.take("environment maps")) {
        Stopwatch clock;
        const bool done = refinementPace_ == RefinementPace::AllAtOnce ? (ownEnvironment_->refine(), true)
                                                                          : ownEnvironment_->refineStep();
        recordOnDemand("environment.prefilter", clock.elapsedMs());
        if (!done) {
            const auto [walked, walks] = ownEnvironment_->refineProgress();
            budget.wait("environment maps " + std::to_string(walked) + "/" + std::to_string(walks));
        }
    }
}

bool Renderer::accumulating() const { return findIblMode(settings_.ibl).accumulates; }

const ReflectionProbes& Renderer::probes() const { return *probes_; }

void Renderer::recordOnDemand(const std::string& name, double ms, bool measurePasses) {
    if (measurePasses) timer_.recordWallOnly(name, ms);
    if (!editPassesOfThisFrame_) editPasses_.clear(), editPassesOfThisFrame_ = true;
    editPasses_.push_back({name, ms, 0.0});
}

void Renderer::uploadFrameUniforms(const Scene& scene, const GpuScene& gpuScene, const View& view,
                                   const glm::mat4& projection) {
    const Camera& camera = view.camera;
    FrameUniforms uniforms{};
    uniforms.view = camera.view();
    uniforms.projection = projection;
    const glm::mat4 viewProjection = projection * uniforms.view;
    // z: the lighting pass moves glint footprints back to the unjittered pixel centre (only on jittered frames, so
    // an unjittered frame is shaded exactly as with aa=off).
    const bool stableGlints = settings_.value(param::taa_stable_glints) > 0.5f && view.jitter != glm::vec2(0.0f);
    // w: the glint footprint's scale, the render size over the output size with lighting.glint_footprint=output
    // (1: the render pixel's footprint).
    float glintFootprint = 1.0f;
    if (settings_.value(param::lighting_glint_footprint) > 0.5f && view.outputWidth > view.width && view.outputWidth > 0)
        glintFootprint = float(view.width) / float(view.outputWidth);
    uniforms.jitter = {view.jitter, stableGlints ? 1.0f : 0.0f, glintFootprint};
    uniforms.viewProjection = viewProjection;
    uniforms.inverseViewProjection = glm::inverse(viewProjection);
    uniforms.cameraPosition = glm::vec4(camera.position, 1.0f);
    uniforms.skyColor = glm::vec4(scene.skyColor, 1.0f);
    uniforms.viewport = {view.width, view.height, int(frameIndex_), settings_.debugView};
    uniforms.exposure = {std::exp2(settings_.value(param::exposure)), float(gpuScene.lightCount()),
                         settings_.value(param::ambient), float(gpuScene.areaLightCount())};
    uniforms.sample = {accumulating() ? view.sampleIndex : 0u, 0u, 0u, 0u};
    glNamedBufferSubData(frameUniforms_.id(), 0, sizeof(uniforms), &uniforms);
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_FRAME, frameUniforms_.id());
    methodOutput_.bind();
}

FrameContext Renderer::frameContext(const Scene& scene, const GpuScene& gpuScene, const View& view, bool blendSample,
                                    const glm::mat4& viewProjection) {
    return FrameContext{
        .scene = scene,
        .gpuScene = gpuScene,
        .view = view,
        .camera = view.camera,
        .settings = settings_,
        .resources = resources_,
        .environment = *environment_,
        .width = view.width,
        .height = view.height,
        .postWidth = view.postWidth,
        .postHeight = view.postHeight,
        .blendSample = blendSample,
        .blendWeight = blendSample ? 1.0f / float(view.sampleIndex + 1) : 1.0f,
        .emptyVao = emptyVao_.id(),
        .viewProjection = viewProjection,
        .temporalAa = view.temporalAa,
    };
}

void Renderer::renderView(const Scene& scene, const GpuScene& gpuScene, View& view, bool measurePasses) {
    if (view.width < 1 || view.height < 1) throw Error("renderView: empty view");
    view.temporalAa = false;
    view.jitter = glm::vec2(0.0f);
    view.postWidth = view.width;
    view.postHeight = view.height;
    if (!resized_ || view.width != lastView_.width || view.height != lastView_.height) {
        for (const auto& pass : frame_) pass->resize(view, resources_);
        resized_ = true;
    }
    timer_.beginFrame(measurePasses     ? PassTimer::Mode::Measure
                      : asyncGpuTimers_ ? PassTimer::Mode::Async
                                        : PassTimer::Mode::Off);
    editPassesOfThisFrame_ = false;
    RefinementBudget refinements = refinementBudget();
    prepareEnvironment(scene, "scene environment", refinements,
                       [&](const std::string& name, double ms) { recordOnDemand(name, ms, measurePasses); });

    // A later sample of an accumulated view reuses the G-buffer of sample 0 and is blended into the mean.
    const bool blendSample = accumulating() && view.sampleIndex > 0;
    PrepareContext prepare{
        .scene = scene,
        .gpuScene = gpuScene,
        .view = view,
        .settings = settings_,
        .environment = *environment_,
        .resources = resources_,
        .blendSample = blendSample,
        .refinements = refinements,
        .recordStats = [&](const std::string& name, double ms) { if (measurePasses) timer_.recordWallOnly(name, ms); },
        .recordOnDemand = [&](const std::string& name, double ms) { recordOnDemand(name, ms, measurePasses); },
    };
    // Passes may render other views here (probes, per-object maps), so the frame's own state is set after.
    for (const auto& pass : frame_) {
        if (prepareListener_) prepareListener_(pass->name());
        pass->prepare(prepare);
    }
    waitingRefinements_ = refinements.waiting();

    // TAA jitters the projection: a screen-space translation (its prepare() chose the jitter).
    glm::mat4 projection = view.camera.projection(view.aspect());
    if (view.jitter != glm::vec2(0.0f))
        projection = image::jitteredProjection(projection, view.jitter, {view.width, view.height});
    const glm::mat4 viewProjection = projection * view.camera.view();
    uploadFrameUniforms(scene, gpuScene, view, projection);
    const FrameContext frame = frameContext(scene, gpuScene, view, blendSample, viewProjection);
    for (const auto& pass : frame_) {
        if (!pass->runs(frame)) continue;
        const PassResources declared = pass->resources();
        PassScope scope(timer_, pass->name());
        resources_.beginPass(pass->name(), &declared);
        pass->execute(frame);
        resources_.endPass();
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    lastView_ = view;
    ++frameIndex_;
}

void Renderer::renderView(const Scene& scene, const GpuScene& gpuScene, const Camera& camera, int width, int height,
                          bool measurePasses) {
    View view{.camera = camera, .width = width, .height = height};
    renderView(scene, gpuScene, view, measurePasses);
}

void Renderer::renderAccumulated(const Scene& scene, const GpuScene& gpuScene, View& view, int samples,
                                 bool measurePasses) {
    samples = accumulating() ? std::max(samples, 1) : 1;
    for (int sample = 0; sample < samples; ++sample) {
        view.sampleIndex = uint32_t(sample);
        renderView(scene, gpuScene, view, measurePasses && sample + 1 == samples);
        if (samples >= 64 && (sample + 1) % (samples / 8) == 0)
            log::info("render: ", sample + 1, " / ", samples, " samples");
    }
}

void Renderer::setExposureAdaptation(float weight) {
    if (exposure_) exposure_->setAdaptation(weight);
}
float Renderer::meteredExposureEv() const { return exposure_ ? exposure_->meteredEv() : 0.0f; }
unsigned Renderer::taaFrames() const { return taa_ ? taa_->framesSinceReset() : 0; }
unsigned Renderer::taaResets() const { return taa_ ? taa_->resets() : 0; }
void Renderer::resetHistory() {
    if (taa_) taa_->reset();
}
GLuint Renderer::displayFramebuffer() const { return tonemap_ ? tonemap_->displayFramebuffer() : 0; }

static std::vector<float> readRgba32f(const FrameImage& image) {
    if (!image.texture()) return {};
    std::vector<float> pixels(size_t(image.width) * size_t(image.height) * 4);
    glGetTextureImage(image.texture(), 0, GL_RGBA, GL_FLOAT, GLsizei(pixels.size() * sizeof(float)), pixels.data());
    return pixels;
}

std::vector<float> Renderer::readHdr() const {
    // The post HDR radiance (TAA's output); a frame list without the image pipeline (captures) has only Hdr.
    const FrameImage& post = resources_.get(FrameResource::PostHdr);
    return readRgba32f(post.texture() ? post : resources_.get(FrameResource::Hdr));
}

std::vector<float> Renderer::readMethodTarget(size_t index) const {
    const FrameImage& targets = resources_.get(FrameResource::MethodTargets);
    if (index >= targets.textures.size()) return {};
    return readRgba32f({.textures = {targets.textures[index]}, .width = targets.width, .height = targets.height});
}

std::vector<float> Renderer::readDepth() const {
    const FrameImage& depth = resources_.get(FrameResource::Depth);
    std::vector<float> pixels(size_t(depth.width) * size_t(depth.height));
    glGetTextureImage(depth.texture(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(pixels.size() * sizeof(float)),
                      pixels.data());
    return pixels;
}

std::vector<uint8_t> Renderer::readDisplay() const {
    const FrameImage& display = resources_.get(FrameResource::Display);
    std::vector<uint8_t> pixels(size_t(display.width) * size_t(display.height) * 4);
    glGetTextureImage(display.texture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    return pixels;
}

}  // namespace glimmer
