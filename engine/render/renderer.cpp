#include "render/renderer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>

#include "core/clock.h"
#include "core/error.h"
#include "gl/debug.h"
#include "glints/methods.h"
#include "render/glint_post.h"
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
    for (gl::Query& q : timerQueries_) {
        GLuint id = 0;
        glCreateQueries(GL_TIME_ELAPSED, 1, &id);
        q = gl::Query(id);
    }
    buildPrograms();
}

gl::ProgramDesc Renderer::lightingDesc() const {
    const GlintMethod& method = findGlintMethod(settings_.method);
    const IblMode& ibl = findIblMode(settings_.ibl);
    checkIblModeMethod(ibl, method.id);
    gl::ProgramDesc desc;
    desc.name = "lighting/" + method.id + (ibl.id == "prefiltered" ? "" : "/" + ibl.id);
    desc.stages = {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "lighting.frag"}};
    desc.defines = {method.define, ibl.define};
    if (method.glintPostPass) desc.defines.push_back("GLINT_POST_PASS");
    desc.preamble = methodParamsGlsl(method) + iblParamsGlsl(ibl);
    desc.includeMacros["GLINT_METHOD_FILE"] = method.shaderFile;
    desc.includeMacros["IBL_MODE_FILE"] = ibl.shaderFile;
    return desc;
}

void Renderer::buildPrograms() {
    // Build all first, then swap: a failure leaves the previous programs in place.
    gl::Program gbuffer(shaderRoot_, {"gbuffer", {{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, "gbuffer.frag"}}});
    gl::Program lighting(shaderRoot_, lightingDesc());
    gl::Program tonemap(shaderRoot_, {"tonemap", {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "tonemap.frag"}}});
    gbufferProgram_ = std::move(gbuffer);
    lightingProgram_ = std::move(lighting);
    tonemapProgram_ = std::move(tonemap);
    buildPostPrograms();
    createMethodResources();
}

void Renderer::buildPostPrograms() {
    if (!findGlintMethod(settings_.method).glintPostPass) {
        occlusionBlurProgram_ = {};
        glintBlurProgram_ = {};
        return;
    }
    gl::Program occlusion(shaderRoot_, {"post/glint_occlusion_blur",
                                        {{GL_VERTEX_SHADER, "fullscreen.vert"},
                                         {GL_FRAGMENT_SHADER, "post/glint_occlusion_blur.frag"}}});
    gl::Program glints(shaderRoot_, {"post/glint_blur",
                                     {{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "post/glint_blur.frag"}}});
    occlusionBlurProgram_ = std::move(occlusion);
    glintBlurProgram_ = std::move(glints);
}

void Renderer::createMethodResources() {
    const GlintMethod& method = findGlintMethod(settings_.method);
    methodResources_ = method.createResources ? method.createResources() : nullptr;
    const IblMode& ibl = findIblMode(settings_.ibl);
    iblResources_ = ibl.createResources ? ibl.createResources() : nullptr;
}

void Renderer::reloadPrograms() {
    try {
        buildPrograms();
        shaderErrors_.clear();
    } catch (const std::exception& e) {
        shaderErrors_["all programs"] = e.what();
        throw;
    }
}

std::vector<gl::Program*> Renderer::programs() {
    std::vector<gl::Program*> all = {&gbufferProgram_, &lightingProgram_, &tonemapProgram_};
    if (occlusionBlurProgram_) all.insert(all.end(), {&occlusionBlurProgram_, &glintBlurProgram_});
    return all;
}
std::vector<const gl::Program*> Renderer::programs() const {
    std::vector<const gl::Program*> all = {&gbufferProgram_, &lightingProgram_, &tonemapProgram_};
    if (occlusionBlurProgram_) all.insert(all.end(), {&occlusionBlurProgram_, &glintBlurProgram_});
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
    bool methodChanged = settings.method != settings_.method || settings.ibl != settings_.ibl;
    RenderSettings previous = settings_;
    settings_ = settings;
    if (methodChanged) {
        try {
            std::string previousName = lightingProgram_.desc().name;
            lightingProgram_ = gl::Program(shaderRoot_, lightingDesc());
            shaderErrors_.erase(previousName);
            buildPostPrograms();
            createMethodResources();
        } catch (...) {
            settings_ = previous;
            throw;
        }
    }
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

void Renderer::render(const Scene& scene, const GpuScene& gpuScene, const Camera& camera, int width, int height,
                      bool measurePasses) {
    prepareEnvironment(scene);
    // IBL-mode resources may render (per-object environment maps), so they update before any state of this frame.
    if (iblResources_)
        iblResources_->prepare(settings_.iblModeValues(settings_.ibl), scene,
                               environment_.enabled() ? environment_.sourceCube() : 0);
    const bool glintPost = bool(occlusionBlurProgram_);
    targets_.resize(width, height, glintPost);
    TimerFrame* timerFrame = asyncGpuTimers_ && !measurePasses ? &asyncTimers_[frameIndex_ % kTimerFrames] : nullptr;
    if (!timerFrame) timings_.clear();
    if (timerFrame && timerFrame->pending) {
        // Read the queries issued kTimerFrames frames ago, only if the last one has finished (never wait).
        GLint available = 0;
        glGetQueryObjectiv(timerFrame->queries[timerFrame->names.size() - 1].id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (available) {
            timings_.clear();
            for (size_t i = 0; i < timerFrame->names.size(); ++i) {
                GLuint64 ns = 0;
                glGetQueryObjectui64v(timerFrame->queries[i].id(), GL_QUERY_RESULT, &ns);
                timings_.push_back({timerFrame->names[i], 0.0, double(ns) * 1e-6});
            }
        }
    }
    if (timerFrame) {
        timerFrame->names.clear();
        timerFrame->pending = false;
    }

    FrameUniforms frame{};
    frame.view = camera.view();
    frame.projection = camera.projection(float(width) / float(height));
    frame.viewProjection = frame.projection * frame.view;
    frame.inverseViewProjection = glm::inverse(frame.viewProjection);
    frame.cameraPosition = glm::vec4(camera.position, 1.0f);
    frame.skyColor = glm::vec4(scene.skyColor, 1.0f);
    frame.viewport = {width, height, int(frameIndex_), settings_.debugView};
    frame.exposure = {std::exp2(settings_.common_("exposure")), float(gpuScene.lightCount()),
                      settings_.common_("ambient"), 0.0f};
    const IblMode& ibl = findIblMode(settings_.ibl);
    // A later sample of an accumulated view reuses the G-buffer of sample 0 and is blended into the mean.
    const bool blendSample = ibl.accumulates && sampleIndex_ > 0;
    frame.sample = {ibl.accumulates ? sampleIndex_ : 0u, 0u, 0u, 0u};
    glNamedBufferSubData(frameUniforms_.id(), 0, sizeof(frame), &frame);
    std::vector<float> params = packMethodParams(findGlintMethod(settings_.method), settings_.methodValues(settings_.method));
    glNamedBufferSubData(methodParams_.id(), 0, GLsizeiptr(params.size() * sizeof(float)), params.data());
    glBindBufferBase(GL_UNIFORM_BUFFER, kFrameBinding, frameUniforms_.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, kMethodParamBinding, methodParams_.id());
    std::vector<float> iblParams = packIblParams(ibl, settings_.iblModeValues(ibl.id));
    glNamedBufferSubData(iblParams_.id(), 0, GLsizeiptr(iblParams.size() * sizeof(float)), iblParams.data());
    glBindBufferBase(GL_UNIFORM_BUFFER, kIblParamBinding, iblParams_.id());

    Stopwatch clock;
    int queryIndex = 0;
    auto beginPass = [&](const char* name) {
        glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name);
        if (measurePasses) {
            glFinish();
            clock.restart();
            if (size_t(queryIndex) >= timerQueries_.size()) {
                GLuint id = 0;
                glCreateQueries(GL_TIME_ELAPSED, 1, &id);
                timerQueries_.emplace_back(id);
            }
            glBeginQuery(GL_TIME_ELAPSED, timerQueries_[size_t(queryIndex)].id());
        } else if (timerFrame) {
            if (timerFrame->names.size() == timerFrame->queries.size()) {
                GLuint id = 0;
                glCreateQueries(GL_TIME_ELAPSED, 1, &id);
                timerFrame->queries.emplace_back(id);
            }
            glBeginQuery(GL_TIME_ELAPSED, timerFrame->queries[timerFrame->names.size()].id());
        }
    };
    auto endPass = [&](const char* name) {
        if (measurePasses) {
            glEndQuery(GL_TIME_ELAPSED);
            glFinish();
            PassTiming t{name, clock.elapsedMs(), 0.0};
            GLuint64 ns = 0;
            glGetQueryObjectui64v(timerQueries_[size_t(queryIndex)].id(), GL_QUERY_RESULT, &ns);
            t.gpuMs = double(ns) * 1e-6;
            timings_.push_back(t);
            ++queryIndex;
        } else if (timerFrame) {
            glEndQuery(GL_TIME_ELAPSED);
            timerFrame->names.push_back(name);
            timerFrame->pending = true;
        }
        glPopDebugGroup();
    };

    glViewport(0, 0, width, height);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);

    // G-buffer: reversed-Z (clear 0, GREATER passes), no blending; GpuScene culls frustum chunks and, on
    // single-sided materials, back faces.
    if (!blendSample) {
        beginPass("gbuffer");
        glBindFramebuffer(GL_FRAMEBUFFER, targets_.gbufferFramebuffer());
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        const float zero[4] = {0, 0, 0, 0};
        for (int i = 0; i < FrameTargets::kGBufferColorCount; ++i) glClearNamedFramebufferfv(targets_.gbufferFramebuffer(), GL_COLOR, i, zero);
        float clearDepth = 0.0f;
        glClearNamedFramebufferfv(targets_.gbufferFramebuffer(), GL_DEPTH, 0, &clearDepth);
        gbufferProgram_.use();
        gpuScene.drawInstances(scene, frame.viewProjection);
        endPass("gbuffer");
    }

    // Parameter-dependent data of the glint method and the IBL mode (tables, trees, the prefiltered environment of
    // wang2020), rebuilt on demand with the environment bound (a mode may prefilter it); the passes that ran are
    // listed in --stats (material editing, Wang et al. 2020 Sec. 4.5).
    if (methodResources_ || iblResources_) {
        environment_.bind(settings_.common_("env.intensity"), settings_.common_("env.rotation"));
        bool cleared = false;
        auto record = [&](const std::vector<std::pair<std::string, double>>& ran) {
            for (const auto& [name, ms] : ran) {
                if (measurePasses) timings_.push_back({name, ms, 0.0});
                if (!cleared) editPasses_.clear(), cleared = true;
                editPasses_.push_back({name, ms, 0.0});
            }
        };
        if (methodResources_) record(methodResources_->update(settings_.methodValues(settings_.method)));
        if (iblResources_ && environment_.enabled()) {
            auto values = settings_.iblValues.find(settings_.ibl);
            record(iblResources_->update(values == settings_.iblValues.end() ? ParamValues{} : values->second));
        }
    }

    beginPass("lighting");
    glBindFramebuffer(GL_FRAMEBUFFER, glintPost ? targets_.lightingGlintFramebuffer() : targets_.hdrFramebuffer());
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    if (blendSample) {
        // Running mean: mean_k = estimate / (k + 1) + mean_{k-1} * k / (k + 1). Only the HDR target blends (the
        // glint post-pass targets hold this sample's glints; their post pass adds them with the same weight).
        glEnablei(GL_BLEND, 0);
        glBlendColor(0.0f, 0.0f, 0.0f, 1.0f / float(sampleIndex_ + 1));
        glBlendFunc(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA);
    }
    lightingProgram_.use();
    if (methodResources_) methodResources_->bind();
    if (iblResources_) iblResources_->bind();
    environment_.bind(settings_.common_("env.intensity"), settings_.common_("env.rotation"));
    for (int i = 0; i < FrameTargets::kGBufferColorCount; ++i) glBindTextureUnit(i, targets_.gbufferTexture(i));
    glBindTextureUnit(5, targets_.depthTexture());
    glBindVertexArray(emptyVao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    endPass("lighting");

    // Wang et al. 2020 Sec. 4.4: blur the directional occlusion (9 taps), multiply, blur the glints (3 taps), add.
    // Debug views have no glints to add.
    if (glintPost && settings_.debugView == 0) {
        const ParamValues values = settings_.methodValues(settings_.method);
        const GlintMethod& method = findGlintMethod(settings_.method);
        auto taps = [&](const char* name) {
            for (const ParamSpec& spec : method.params)
                if (spec.name == name) return int(paramOr(values, spec) + 0.5f);
            throw Error(method.id + ": glint post pass needs the parameter " + name);
        };
        const int occlusionRadius = glintpost::radiusOf(taps("blur_occlusion"));
        const int glintRadius = glintpost::radiusOf(taps("blur_glints"));
        auto setKernel = [](const gl::Program& program, int radius) {
            std::vector<float> weights = glintpost::binomialWeights(radius);
            glProgramUniform1i(program.id(), 1, radius);
            glProgramUniform1fv(program.id(), 2, GLsizei(weights.size()), weights.data());
        };
        beginPass("glint_occlusion_blur");
        occlusionBlurProgram_.use();
        setKernel(occlusionBlurProgram_, occlusionRadius);
        glBindTextureUnit(0, targets_.glintEnvironmentTexture());
        glBindTextureUnit(1, targets_.glintLightsTexture());
        glBindFramebuffer(GL_FRAMEBUFFER, targets_.occlusionSumsFramebuffer());
        glProgramUniform1i(occlusionBlurProgram_.id(), 0, 0);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindTextureUnit(2, targets_.occlusionSumsTexture());
        glBindFramebuffer(GL_FRAMEBUFFER, targets_.occludedGlintFramebuffer());
        glProgramUniform1i(occlusionBlurProgram_.id(), 0, 1);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        endPass("glint_occlusion_blur");

        beginPass("glint_blur");
        glintBlurProgram_.use();
        setKernel(glintBlurProgram_, glintRadius);
        glBindTextureUnit(0, targets_.occludedGlintTexture());
        glBindFramebuffer(GL_FRAMEBUFFER, targets_.hdrFramebuffer());
        glEnable(GL_BLEND);
        glBlendColor(0.0f, 0.0f, 0.0f, blendSample ? 1.0f / float(sampleIndex_ + 1) : 1.0f);
        glBlendFuncSeparate(GL_CONSTANT_ALPHA, GL_ONE, GL_ZERO, GL_ONE);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDisable(GL_BLEND);
        endPass("glint_blur");
    }

    beginPass("tonemap");
    glBindFramebuffer(GL_FRAMEBUFFER, targets_.displayFramebuffer());
    tonemapProgram_.use();
    glBindTextureUnit(0, targets_.hdrTexture());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    endPass("tonemap");

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
