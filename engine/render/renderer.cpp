#include "render/renderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>

#include "core/error.h"
#include "gl/debug.h"
#include "glints/methods.h"
#include "common/bindings.glsl"
#include "render/passes/gbuffer_pass.h"
#include "render/passes/lighting_pass.h"
#include "render/passes/method_pass_host.h"
#include "render/passes/tonemap_pass.h"
#include "render/renderer_capture.h"
#include "render/shader_interface.h"

namespace glimmer {

Renderer::Renderer(std::filesystem::path shaderRoot, const RenderSettings& settings)
    : shaderRoot_(std::move(shaderRoot)), settings_(settings), environment_(shaderRoot_) {
    gl::enableDebugOutput();
    frameUniforms_ = gl::createBuffer(sizeof(FrameUniforms), nullptr);
    methodParams_ = gl::createBuffer(kMaxMethodParams * sizeof(float), nullptr);
    iblParams_ = gl::createBuffer(kMaxIblParams * sizeof(float), nullptr);
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    emptyVao_ = gl::VertexArray(vao);
    capture_ = std::make_unique<RendererCapture>(shaderRoot_);
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
    auto gbuffer = std::make_unique<GBufferPass>(shaderRoot_);
    auto lighting = std::make_unique<LightingPass>(shaderRoot_, settings_.method, settings_.ibl);
    auto methodPasses = methodPassesOf(findGlintMethod(settings_.method), shaderRoot_);
    auto tonemap = std::make_unique<TonemapPass>(shaderRoot_);
    gbufferPass_ = std::move(gbuffer);
    lightingPass_ = std::move(lighting);
    methodPasses_ = std::move(methodPasses);
    tonemapPass_ = std::move(tonemap);
    createMethodResources();
}

void Renderer::createMethodResources() {
    const GlintMethod& method = findGlintMethod(settings_.method);
    methodResources_ = method.createResources ? method.createResources() : nullptr;
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
    std::vector<Pass*> passes = {gbufferPass_.get(), lightingPass_.get()};
    for (const auto& pass : methodPasses_) passes.push_back(pass.get());
    passes.push_back(tonemapPass_.get());
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
        try {
            gl::Program fresh(shaderRoot_, program->desc());
            *program = std::move(fresh);  // swap only after a successful link
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
    const bool methodChanged = settings.method != settings_.method || settings.ibl != settings_.ibl;
    if (!methodChanged) {
        settings_ = settings;
        return;
    }
    // Build the new method's passes first: a failure keeps the previous method running.
    auto lighting = std::make_unique<LightingPass>(shaderRoot_, settings.method, settings.ibl);
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
    bool cleared = false;
    auto record = [&](const std::vector<std::pair<std::string, double>>& ran) {
        for (const auto& [name, ms] : ran) {
            if (measurePasses) timer_.recordWallOnly(name, ms);
            if (!cleared) editPasses_.clear(), cleared = true;
            editPasses_.push_back({name, ms, 0.0});
        }
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
    for (const Material& m : scene.materials) {
        std::vector<float> row = packMethodParams(method, materialParams(method, m, overrides));
        rows.insert(rows.end(), row.begin(), row.end());
    }
    if (rows.empty()) rows = shared;
    const GLsizeiptr bytes = GLsizeiptr(rows.size() * sizeof(float));
    if (bytes > materialMethodParamsBytes_) {
        materialMethodParams_ = gl::createBuffer(bytes, nullptr);
        materialMethodParamsBytes_ = bytes;
    }
    glNamedBufferSubData(materialMethodParams_.id(), 0, bytes, rows.data());
}

void Renderer::runPass(Pass& pass, const FrameContext& frame) {
    if (!pass.runs(frame)) return;
    PassScope scope(timer_, pass.name());
    pass.execute(frame);
}

void Renderer::render(const Scene& scene, const GpuScene& gpuScene, const Camera& camera, int width, int height,
                      bool measurePasses) {
    prepareEnvironment(scene);
    // IBL-mode resources may render (per-object environment maps), so they update before any state of this frame.
    if (iblResources_)
        iblResources_->prepare(settings_.iblModeValues(settings_.ibl), scene,
                               environment_.enabled() ? environment_.sourceCube() : 0, *capture_);
    targets_.resize(width, height, findGlintMethod(settings_.method).glintPostPass);
    timer_.beginFrame(measurePasses     ? PassTimer::Mode::Measure
                      : asyncGpuTimers_ ? PassTimer::Mode::Async
                                        : PassTimer::Mode::Off);

    const IblMode& ibl = findIblMode(settings_.ibl);
    // A later sample of an accumulated view reuses the G-buffer of sample 0 and is blended into the mean.
    const bool blendSample = ibl.accumulates && sampleIndex_ > 0;
    FrameUniforms uniforms{};
    uniforms.view = camera.view();
    uniforms.projection = camera.projection(float(width) / float(height));
    uniforms.viewProjection = uniforms.projection * uniforms.view;
    uniforms.inverseViewProjection = glm::inverse(uniforms.viewProjection);
    uniforms.cameraPosition = glm::vec4(camera.position, 1.0f);
    uniforms.skyColor = glm::vec4(scene.skyColor, 1.0f);
    uniforms.viewport = {width, height, int(frameIndex_), settings_.debugView};
    uniforms.exposure = {std::exp2(settings_.common_("exposure")), float(gpuScene.lightCount()),
                         settings_.common_("ambient"), 0.0f};
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
                             uniforms.viewProjection};
    runPass(*gbufferPass_, frame);
    updateMethodData(measurePasses);
    runPass(*lightingPass_, frame);
    for (const auto& pass : methodPasses_) runPass(*pass, frame);   // e.g. Wang et al. 2020 Sec. 4.4 post pass
    runPass(*tonemapPass_, frame);

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    ++frameIndex_;
}

std::vector<float> Renderer::readHdr() const {
    std::vector<float> pixels(size_t(targets_.width()) * targets_.height() * 4);
    glGetTextureImage(targets_.hdrTexture(), 0, GL_RGBA, GL_FLOAT, GLsizei(pixels.size() * sizeof(float)), pixels.data());
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
    std::vector<uint8_t> pixels(size_t(targets_.width()) * targets_.height() * 4);
    glGetTextureImage(targets_.displayTexture(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
    return pixels;
}

}  // namespace glimmer
