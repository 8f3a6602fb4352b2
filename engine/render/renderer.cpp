#include "render/renderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>

#include "core/error.h"
#include "gl/debug.h"
#include "glints/methods.h"
#include "common/bindings.glsl"
#include "render/ao/ambient_occlusion.h"
#include "render/ao/ao_resolve_pass.h"
#include "render/frame/gbuffer_pass.h"
#include "render/ao/gtao_pass.h"
#include "render/frame/lighting_pass.h"
#include "render/frame/method_pass_host.h"
#include "render/image/bloom_pass.h"
#include "render/image/exposure_pass.h"
#include "render/image/taa_pass.h"
#include "render/shadows/shadow_map_pass.h"
#include "render/shadows/shadow_mask_pass.h"
#include "render/image/tonemap_pass.h"
#include "render/image/halton_jitter.h"
#include "render/forward/emissive_pass.h"
#include "render/forward/forward_target.h"
#include "render/forward/transparent_pass.h"
#include "render/renderer_capture.h"
#include "render/shader_interface.h"
#include "render/shadows/shadow_maps.h"

namespace glimmer {

Renderer::Renderer(std::filesystem::path shaderRoot, const RenderSettings& settings)
    : shaderRoot_(std::move(shaderRoot)), settings_(settings), environment_(shaderRoot_), environmentGlints_(shaderRoot_) {
    gl::enableDebugOutput();
    frameUniforms_ = gl::createBuffer(sizeof(FrameUniforms), nullptr);
    methodParams_ = gl::createBuffer(kMaxMethodParams * sizeof(float), nullptr);
    iblParams_ = gl::createBuffer(kMaxIblParams * sizeof(float), nullptr);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    emptyVao_ = gl::VertexArray(vao);
    capture_ = std::make_unique<RendererCapture>(shaderRoot_);
    probes_ = std::make_unique<ReflectionProbes>(shaderRoot_);
    ambientOcclusion_ = std::make_unique<AmbientOcclusion>();
    shadowMaps_ = std::make_unique<ShadowMaps>();
    buildPasses();
}

Renderer::~Renderer() = default;

static std::vector<std::unique_ptr<Pass>> methodPassesOf(const GlintMethod& method, const std::filesystem::path& root) {
    std::vector<std::unique_ptr<Pass>> passes;
    if (method.createPasses)
        for (std::unique_ptr<MethodPass>& pass : method.createPasses(root))
            passes.push_back(std::make_unique<MethodPassHost>(std::move(pass)));
    return passes;
}

void Renderer::buildPasses() {
    // Build all first, then swap: a failure leaves the previous passes in place.
    auto sunShadow = std::make_unique<ShadowMapPass>(shaderRoot_, ShadowArray::Sun);
    auto pointShadow = std::make_unique<ShadowMapPass>(shaderRoot_, ShadowArray::Local);
    auto gbuffer = std::make_unique<GBufferPass>(shaderRoot_);
    auto gtao = std::make_unique<GtaoPass>(shaderRoot_, *ambientOcclusion_);
    auto aoResolve = std::make_unique<AoResolvePass>(shaderRoot_, *ambientOcclusion_);
    auto shadowMask = std::make_unique<ShadowMaskPass>(shaderRoot_);
    auto lighting = std::make_unique<LightingPass>(shaderRoot_, settings_.method, settings_.ibl,
                                                   settings_.common_("shadow.enabled") > 0.5f);
    auto methodPasses = methodPassesOf(findGlintMethod(settings_.method), shaderRoot_);
    auto taa = std::make_unique<TaaPass>(shaderRoot_);
    auto exposure = std::make_unique<ExposurePass>(shaderRoot_);
    auto bloom = std::make_unique<BloomPass>(shaderRoot_);
    auto tonemap = std::make_unique<TonemapPass>(shaderRoot_, *bloom, *exposure);
    auto forwardTarget = std::make_shared<ForwardTarget>();
    auto emissive = std::make_unique<EmissivePass>(shaderRoot_, forwardTarget);
    auto transparent = std::make_unique<TransparentPass>(shaderRoot_, forwardTarget);
    sunShadowPass_ = std::move(sunShadow);
    pointShadowPass_ = std::move(pointShadow);
    forwardRestorePass_ = std::make_unique<ForwardAccumulationPass>(forwardTarget, ForwardAccumulationPass::Mode::Restore);
    forwardSavePass_ = std::make_unique<ForwardAccumulationPass>(forwardTarget, ForwardAccumulationPass::Mode::Save);
    forwardTarget_ = std::move(forwardTarget);
    emissivePass_ = std::move(emissive);
    transparentPass_ = std::move(transparent);
    gbufferPass_ = std::move(gbuffer);
    gtaoPass_ = std::move(gtao);
    aoResolvePass_ = std::move(aoResolve);
    shadowMaskPass_ = std::move(shadowMask);
    lightingPass_ = std::move(lighting);
    methodPasses_ = std::move(methodPasses);
    tonemapPass_ = std::move(tonemap);   // before the passes it refers to are replaced
    taaPass_ = std::move(taa);
    exposurePass_ = std::move(exposure);
    bloomPass_ = std::move(bloom);
    shadowMaps_->invalidate();   // the maps were drawn by the previous depth program
    createMethodResources();
}

void Renderer::createMethodResources() {
    const GlintMethod& method = findGlintMethod(settings_.method);
    methodResources_ = method.createResources ? method.createResources() : nullptr;
    methodResourcesFrom_ = method.resourcesFrom;
    const IblMode& ibl = findIblMode(settings_.ibl);
    iblResources_ = ibl.createResources ? ibl.createResources() : nullptr;
}

void Renderer::reloadPrograms() {
    try {
        buildPasses();
        shaderErrors_.clear();
    } catch (const std::exception& e) {
        shaderErrors_["all programs"] = e.what();
        throw;
    }
}

std::vector<Pass*> Renderer::frame() const {
    std::vector<Pass*> passes = {sunShadowPass_.get(),  pointShadowPass_.get(),    gbufferPass_.get(),
                                 gtaoPass_.get(),       aoResolvePass_.get(),      shadowMaskPass_.get(),
                                 forwardRestorePass_.get(), lightingPass_.get()};
    for (const auto& pass : methodPasses_) passes.push_back(pass.get());
    passes.insert(passes.end(), {forwardSavePass_.get(), emissivePass_.get(), transparentPass_.get(),
                                 taaPass_.get(), exposurePass_.get(), bloomPass_.get(), tonemapPass_.get()});
    return passes;
}

std::vector<gl::Program*> Renderer::programs() const {
    std::vector<gl::Program*> all;
    for (Pass* pass : frame())
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
        const bool lighting = program == lightingPass_->programs().front();
        try {
            gl::Program fresh(shaderRoot_, lighting ? lightingProgramDesc(settings_.method, settings_.ibl, lightingPass_->shadows())
                                                    : program->desc());
            *program = std::move(fresh);  // swap only after a successful link
            if (name == "shadow_depth") shadowMaps_->invalidate();
            shaderErrors_.erase(name);
            shaderErrors_.erase("all programs");
            rebuilt.push_back(name);
            if (lighting && findGlintMethod(settings_.method).resourcesFrom != methodResourcesFrom_) createMethodResources();
        } catch (const std::exception& e) {
            shaderErrors_[name] = e.what();
        }
    }
    return rebuilt;
}

void Renderer::setSettings(const RenderSettings& settings) {
    const bool shadows = settings.common_("shadow.enabled") > 0.5f;
    const bool methodChanged = settings.method != settings_.method || settings.ibl != settings_.ibl;
    // Any edit is a cut for TAA: the history shows the old image.
    if (methodChanged || settings.common != settings_.common || settings.methods != settings_.methods ||
        settings.debugView != settings_.debugView || settings.iblValues != settings_.iblValues)
        taaPass_->reset();
    if (!methodChanged && shadows == lightingPass_->shadows()) {
        settings_ = settings;
        return;
    }
    if (!methodChanged) {   // shadows toggled: only the lighting program changes
        auto lighting = std::make_unique<LightingPass>(shaderRoot_, settings.method, settings.ibl, shadows);
        settings_ = settings;
        lightingPass_ = std::move(lighting);
        return;
    }
    // Build the new method's passes first: a failure keeps the previous method running.
    auto lighting = std::make_unique<LightingPass>(shaderRoot_, settings.method, settings.ibl, shadows);
    auto methodPasses = methodPassesOf(findGlintMethod(settings.method), shaderRoot_);
    const std::string previousName = lightingPass_->programs().front()->desc().name;
    settings_ = settings;
    lightingPass_ = std::move(lighting);
    methodPasses_ = std::move(methodPasses);
    shaderErrors_.erase(previousName);
    createMethodResources();
}

std::vector<std::filesystem::path> Renderer::shaderDependencies() const {
    std::vector<std::filesystem::path> all;
    for (const gl::Program* p : programs())
        for (const auto& f : p->dependencies())
            if (std::find(all.begin(), all.end(), f) == all.end()) all.push_back(f);
    return all;
}

void Renderer::prepareEnvironment(const Scene& scene, const std::string& flag) {
    environment_.update(scene.environment, sunFromScene(scene), flag);
}

void Renderer::updateMethodData(bool measurePasses) {
    if (!methodResources_ && !iblResources_) return;
    environment_.bind(settings_.common_("env.intensity"), settings_.common_("env.rotation"));
    auto record = [&](const std::vector<std::pair<std::string, double>>& ran) {
        for (const auto& [name, ms] : ran) recordOnDemand(name, ms, measurePasses);
    };
    if (methodResources_) record(methodResources_->update(sharedMethodValues_));
    if (iblResources_ && environment_.enabled())
        record(iblResources_->update(settings_.iblModeValues(settings_.ibl), methodResources_.get()));
}

// The method's parameters of every material (glint material mapped, --set overrides on top: glint_mapping.h)
// and the shared values its GPU data are built from.
void Renderer::uploadMethodParams(const Scene& scene) {
    const GlintMethod& method = findGlintMethod(settings_.method);
    const ParamValues& overrides = settings_.methodValues(settings_.method);
    sharedMethodValues_ = sharedParams(method, scene.materials, overrides);
    std::vector<float> shared = packMethodParams(method, sharedMethodValues_);
    glNamedBufferSubData(methodParams_.id(), 0, GLsizeiptr(shared.size() * sizeof(float)), shared.data());
    std::vector<float> rows;
    rows.reserve((scene.materials.size() + 1) * kMaxMethodParams);
    std::vector<ParamValues> perMaterial;
    perMaterial.reserve(scene.materials.size());
    for (const Material& m : scene.materials) {
        perMaterial.push_back(materialParams(method, m, overrides));
        std::vector<float> row = packMethodParams(method, perMaterial.back());
        rows.insert(rows.end(), row.begin(), row.end());
        if (!m.glinty) perMaterial.back().clear();
    }
    if (methodResources_) methodResources_->setMaterials(perMaterial);
    if (rows.empty()) rows = shared;
    const GLsizeiptr bytes = GLsizeiptr(rows.size() * sizeof(float));
    if (bytes > materialMethodParamsBytes_) {
        materialMethodParams_ = gl::createBuffer(bytes, nullptr);
        materialMethodParamsBytes_ = bytes;
    }
    glNamedBufferSubData(materialMethodParams_.id(), 0, bytes, rows.data());
}

void Renderer::recordOnDemand(const std::string& name, double ms, bool measurePasses) {
    if (measurePasses) timer_.recordWallOnly(name, ms);
    if (!editPassesOfThisFrame_) editPasses_.clear(), editPassesOfThisFrame_ = true;
    editPasses_.push_back({name, ms, 0.0});
}

void Renderer::runPass(Pass& pass, const FrameContext& frame) {
    if (!pass.runs(frame)) return;
    PassScope scope(timer_, pass.name());
    pass.execute(frame);
}

void Renderer::render(const Scene& scene, const GpuScene& gpuScene, const Camera& camera, int width, int height,
                      bool measurePasses) {
    prepareEnvironment(scene);
    ltcTable_.bind();   // on its own unit: every lighting program of the frame reads it, probe captures included
    environmentGlints_.bind(false);   // probe captures draw no environment glints (bound again below)
    // IBL-mode resources may render (per-object environment maps), so they update before any state of this frame.
    if (iblResources_)
        iblResources_->prepare(settings_.iblModeValues(settings_.ibl), scene,
                               environment_.enabled() ? environment_.sourceCube() : 0, *capture_);
    const bool temporalAa = TaaPass::wanted(settings_);
    const IblMode& ibl = findIblMode(settings_.ibl);
    // Reflection probes for modes that read them, re-captured only when what they see changed; like the
    // IBL-mode resources above they render, so they run before this frame's state is set.
    const bool probesActive = ibl.readsProbes && environment_.enabled() && probeSettings(settings_).enabled;
    ReflectionProbes::Update probeUpdate;
    if (probesActive) probeUpdate = probes_->update(scene, gpuScene, environment_, settings_);
    targets_.resize(width, height, findGlintMethod(settings_.method).glintPostPass, temporalAa);
    // TAA upsampling: the history, the post passes and the display image at the output size.
    // taa.upsample=0 resolves at the render size (the post passes then run on 1 / scale^2 fewer pixels) and leaves
    // the upscale to the caller.
    const bool upsample = temporalAa && settings_.common_("taa.upsample") > 0.5f &&
                          outputWidth_ >= width && outputHeight_ >= height &&
                          (outputWidth_ > width || outputHeight_ > height);
    const int postWidth = upsample ? outputWidth_ : width, postHeight = upsample ? outputHeight_ : height;
    targets_.resizePost(postWidth, postHeight);
    timer_.beginFrame(measurePasses     ? PassTimer::Mode::Measure
                      : asyncGpuTimers_ ? PassTimer::Mode::Async
                                        : PassTimer::Mode::Off);
    editPassesOfThisFrame_ = false;
    if (probeUpdate.ran) {
        recordOnDemand("probes.capture", probeUpdate.captureMs, measurePasses);
        recordOnDemand("probes.prefilter", probeUpdate.prefilterMs, measurePasses);
    }
    // Environment glints (Kneiphof & Klein 2025) for a method that draws them under an IBL mode that has the
    // levels parameter: rebuilt only when the environment, the probes or the parameters changed.
    const EnvironmentGlintSettings glintSettings = environmentGlintSettings(ibl, settings_.iblModeValues(ibl.id));
    const bool environmentGlints = findGlintMethod(settings_.method).environmentGlints && glintSettings.levels > 0 &&
                                   environment_.enabled();
    if (environmentGlints)
        for (const auto& [name, ms] :
             environmentGlints_.update(glintSettings, environment_.sourceCube(), Environment::kFaceSize, environment_.key(),
                                       probesActive ? EnvironmentGlints::Probes{probes_->specularArray(),
                                                                                int(probes_->probes().size()),
                                                                                probes_->captures()}
                                                    : EnvironmentGlints::Probes{},
                                       measurePasses))
            recordOnDemand(name, ms, measurePasses);
    environmentGlints_.bind(environmentGlints);

    // Sky visibility of a new scene (baked or loaded from the cache) before any pass of this frame.
    for (const PassTiming& ran : ambientOcclusion_->prepare(settings_, scene, gpuScene.serial(), width, height))
        if (measurePasses) timer_.recordWallOnly(ran.name, ran.wallMs);

    // A later sample of an accumulated view reuses the G-buffer of sample 0 and is blended into the mean.
    const bool blendSample = ibl.accumulates && sampleIndex_ > 0;
    FrameUniforms uniforms{};
    uniforms.view = camera.view();
    uniforms.projection = camera.projection(float(width) / float(height));
    // TAA jitters the projection: a screen-space translation, so UV derivatives and glint footprints stay those
    // of the unjittered pixel (docs/image.md). AOVs and accumulating IBL modes stay unjittered.
    lastJitter_ = glm::vec2(0.0f);
    if (temporalAa) {
        const glm::vec3 forward = -glm::vec3(glm::inverse(uniforms.view)[2]);
        lastJitter_ = taaPass_->beginFrame(uniforms.projection * uniforms.view, camera.position, forward, width, height,
                                           postWidth, postHeight);
        uniforms.projection = image::jitteredProjection(uniforms.projection, lastJitter_, {width, height});
    } else {
        taaPass_->reset();
    }
    // z: the lighting pass moves glint footprints back to the unjittered pixel centre (only on jittered frames, so
    // an unjittered frame is shaded exactly as with aa=off).
    const bool stableGlints = settings_.common_("taa.stable_glints") > 0.5f && lastJitter_ != glm::vec2(0.0f);
    uniforms.jitter = {lastJitter_, stableGlints ? 1.0f : 0.0f, 0.0f};
    uniforms.viewProjection = uniforms.projection * uniforms.view;
    uniforms.inverseViewProjection = glm::inverse(uniforms.viewProjection);
    uniforms.cameraPosition = glm::vec4(camera.position, 1.0f);
    uniforms.skyColor = glm::vec4(scene.skyColor, 1.0f);
    uniforms.viewport = {width, height, int(frameIndex_), settings_.debugView};
    uniforms.exposure = {std::exp2(settings_.common_("exposure")), float(gpuScene.lightCount()),
                         settings_.common_("ambient"), float(gpuScene.areaLightCount())};
    uniforms.sample = {ibl.accumulates ? sampleIndex_ : 0u, 0u, 0u, 0u};
    glNamedBufferSubData(frameUniforms_.id(), 0, sizeof(uniforms), &uniforms);
    uploadMethodParams(scene);
    std::vector<float> iblParams = packIblParams(ibl, settings_.iblModeValues(ibl.id));
    glNamedBufferSubData(iblParams_.id(), 0, GLsizeiptr(iblParams.size() * sizeof(float)), iblParams.data());
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_FRAME, frameUniforms_.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_METHOD_PARAMS, methodParams_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_MATERIAL_METHOD_PARAMS, materialMethodParams_.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_IBL_PARAMS, iblParams_.id());

    const FrameContext frame{scene,        gpuScene,     camera,   settings_, targets_,
                             environment_, methodResources_.get(), iblResources_.get(),
                             width,        height,       blendSample,
                             blendSample ? 1.0f / float(sampleIndex_ + 1) : 1.0f, emptyVao_.id(),
                             uniforms.viewProjection,
                             temporalAa, probes_.get(), probesActive, ambientOcclusion_->occlusionTexture(),
                             shadowMaps_.get()};
    // Shadow views first (fitted to this camera; only the invalidated ones are rendered).
    if (!blendSample) shadowMaps_->prepare(scene, gpuScene, camera, float(width) / float(height), settings_);
    runPass(*sunShadowPass_, frame);
    runPass(*pointShadowPass_, frame);
    gpuScene.setTextureAnisotropy(settings_.common_("texture_anisotropy"));
    runPass(*gbufferPass_, frame);
    runPass(*gtaoPass_, frame);
    runPass(*aoResolvePass_, frame);
    updateMethodData(measurePasses);
    runPass(*forwardRestorePass_, frame);   // accumulating IBL modes: the opaque mean without last sample's composite
    runPass(*shadowMaskPass_, frame);       // every shadowed light's visibility (shadow.half_res: every 2nd pixel)
    runPass(*lightingPass_, frame);
    for (const auto& pass : methodPasses_) runPass(*pass, frame);   // e.g. Wang et al. 2020 Sec. 4.4 post pass
    runPass(*forwardSavePass_, frame);
    runPass(*emissivePass_, frame);         // emission of opaque and masked materials
    runPass(*transparentPass_, frame);      // glTF BLEND surfaces, back to front
    runPass(*taaPass_, frame);
    runPass(*exposurePass_, frame);
    runPass(*bloomPass_, frame);
    runPass(*tonemapPass_, frame);

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    ++frameIndex_;
}

void Renderer::setExposureAdaptation(float weight) { exposurePass_->setAdaptation(weight); }
float Renderer::meteredExposureEv() const { return exposurePass_->meteredEv(); }
unsigned Renderer::taaFrames() const { return taaPass_->framesSinceReset(); }
unsigned Renderer::taaResets() const { return taaPass_->resets(); }
void Renderer::resetHistory() { taaPass_->reset(); }

std::vector<float> Renderer::readHdr() const {
    std::vector<float> pixels(size_t(targets_.postWidth()) * targets_.postHeight() * 4);
    glGetTextureImage(targets_.postHdrTexture(), 0, GL_RGBA, GL_FLOAT, GLsizei(pixels.size() * sizeof(float)), pixels.data());
    return pixels;
}

static std::vector<float> readRgba32f(GLuint texture, int width, int height) {
    if (!texture) return {};
    std::vector<float> pixels(size_t(width) * size_t(height) * 4);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(pixels.size() * sizeof(float)), pixels.data());
    return pixels;
}
std::vector<float> Renderer::readGlintEnvironment() const {
    return readRgba32f(targets_.glintEnvironmentTexture(), targets_.width(), targets_.height());
}
std::vector<float> Renderer::readGlintLights() const {
    return readRgba32f(targets_.glintLightsTexture(), targets_.width(), targets_.height());
}

std::vector<uint8_t> Renderer::readDisplay() const {
    std::vector<uint8_t> pixels(size_t(targets_.postWidth()) * targets_.postHeight() * 4);
    glGetTextureImage(targets_.displayTexture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    return pixels;
}

}  // namespace glimmer
