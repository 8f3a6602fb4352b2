#include "render/frame/lighting_pass.h"

#include "common/bindings.glsl"
#include "core/clock.h"
#include "gl/pipeline_state.h"
#include "glints/glint_mapping.h"
#include "render/probes/reflection_probes.h"
#include "render/shadows/shadow_maps.h"

namespace glimmer {

bool sceneHasClearcoat(const Scene& scene) {
    for (const Material& m : scene.materials)
        if (m.clearcoat > 0.0f) return true;
    return false;
}

gl::ProgramDesc lightingProgramDesc(const std::string& methodId, const std::string& iblId, bool shadows,
                                    bool nonGlinty, bool clearcoat, const ParamValues& constantChoices) {
    const GlintMethod& method = findGlintMethod(methodId);
    const IblMode& ibl = findIblMode(iblId);
    checkIblModeMethod(ibl, method.id);
    gl::ProgramDesc desc;
    desc.name = "lighting/" + method.id + (ibl.id == "prefiltered" ? "" : "/" + ibl.id);
    desc.stages = {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "frame/lighting.frag"}};
    desc.defines = {method.define, ibl.define};
    // The method writes targets of its own (shaders/glints/README.md, "Lighting targets").
    if (!method.lightingTargets.empty()) desc.defines.push_back("GLINT_METHOD_TARGETS");
    // The method filters over the pixel's range of half vectors / reads LEAN-filtered normal maps (methods.h).
    if (method.surfaceDerivatives) desc.defines.push_back("GLINT_SURFACE_DERIVATIVES");
    if (method.slopeCovariance) desc.defines.push_back("GLINT_SLOPE_COVARIANCE");
    if (shadows) desc.defines.push_back("SHADOWS");
    if (clearcoat) desc.defines.push_back("SCENE_CLEARCOAT");
    if (nonGlinty) {
        static const std::string nonGlintyDefine = "NON_GLINTY_PIXELS";   // (a named string: GCC 12's -Warray-bounds
        desc.defines.push_back(nonGlintyDefine);                          // misfires on the literal's temporary)
        desc.name += "/non-glinty";
    }
    desc.preamble = methodParamsGlsl(method, true, constantChoices) + iblParamsGlsl(ibl);
    desc.includeMacros["GLINT_METHOD_FILE"] = method.shaderFile;
    desc.includeMacros["IBL_MODE_FILE"] = ibl.shaderFile;
    return desc;
}

LightingPass::LightingPass(const std::filesystem::path& shaderRoot, const RenderSettings& settings,
                           ibl::SceneCapture& capture)
    : shaderRoot_(shaderRoot),
      methodId_(settings.method),
      iblId_(settings.ibl),
      shadows_(settings.value(param::shadow_enabled) > 0.5f),
      capture_(capture),
      program_(shaderRoot, programDesc(false)) {
    methodParams_ = gl::createBuffer(kMaxMethodParams * sizeof(float), nullptr);
    iblParams_ = gl::createBuffer(kMaxIblParams * sizeof(float), nullptr);
    createMethodResources();
}

LightingPass::~LightingPass() = default;

void LightingPass::createMethodResources() {
    const GlintMethod& method = findGlintMethod(methodId_);
    methodResources_ = method.createResources ? method.createResources() : nullptr;
    methodResourcesFrom_ = method.resourcesFrom;
    const IblMode& ibl = findIblMode(iblId_);
    iblResources_ = ibl.createResources ? ibl.createResources() : nullptr;
}

gl::ProgramDesc LightingPass::programDesc(bool nonGlinty) const {
    return lightingProgramDesc(methodId_, iblId_, shadows_, nonGlinty, clearcoat_, constantChoices_);
}

void LightingPass::rebuildVariant() {
    gl::Program fresh(shaderRoot_, programDesc(false));
    program_ = std::move(fresh);   // swap only after a successful link
    nonGlintyProgram_.reset();     // rebuilt on the next split frame
}

bool LightingPass::rebuildProgram() {
    rebuildVariant();
    if (findGlintMethod(methodId_).resourcesFrom == methodResourcesFrom_) return false;
    createMethodResources();
    return true;
}

void LightingPass::setShadows(bool shadows) {
    const bool previous = shadows_;
    shadows_ = shadows;
    try {
        rebuildVariant();
    } catch (...) {
        shadows_ = previous;   // the programs in use still match the state
        throw;
    }
}

PassResources LightingPass::resources() const {
    return {.reads = {FrameResource::GBuffer, FrameResource::Depth, FrameResource::ShadowMaps,
                      FrameResource::ShadowMask, FrameResource::AmbientOcclusion, FrameResource::ReflectionProbes,
                      FrameResource::EnvironmentGlints},
            .writes = {FrameResource::ShadingClass, FrameResource::Hdr, FrameResource::GlintPart,
                       FrameResource::MethodTargets}};
}

std::vector<gl::Program*> LightingPass::programs() {
    std::vector<gl::Program*> all{&program_};
    if (nonGlintyProgram_) all.push_back(nonGlintyProgram_.get());
    if (classProgram_) all.push_back(classProgram_.get());
    return all;
}

void LightingPass::buildSplitPrograms() {
    nonGlintyProgram_ =
        std::make_unique<gl::Program>(shaderRoot_, programDesc(true));
    if (!classProgram_)
        classProgram_ = std::make_unique<gl::Program>(
            shaderRoot_, gl::ProgramDesc{"lighting class", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                            {GL_FRAGMENT_SHADER, "frame/lighting_class.frag"}}});
}

void LightingPass::resize(const View& view, FrameResources& resources) {
    hdr_ = gl::createTexture2D(GL_RGBA32F, view.width, view.height);
    shadingClass_ = gl::createTexture2D(GL_DEPTH_COMPONENT16, view.width, view.height);
    resources.publish(FrameResource::Hdr, {.textures = {hdr_.id()}, .width = view.width, .height = view.height});
    resources.publish(FrameResource::ShadingClass,
                      {.textures = {shadingClass_.id()}, .width = view.width, .height = view.height});
    FrameImage targets{.width = view.width, .height = view.height};
    methodTargets_.clear();
    for (const MethodTarget& target : findGlintMethod(methodId_).lightingTargets) {
        methodTargets_.push_back(gl::createTexture2D(target.format, view.width, view.height));
        targets.textures.push_back(methodTargets_.back().id());
    }
    resources.publish(FrameResource::MethodTargets, std::move(targets));
}

void LightingPass::uploadMethodParams(const Scene& scene, const RenderSettings& settings) {
    const GlintMethod& method = findGlintMethod(methodId_);
    const ParamValues& overrides = settings.methodValues(methodId_);
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
    }
    // Enumerations every material shares (every row of the buffer) compile as constants; a scene or an edit that
    // changes them rebuilds the programs (prepare()).
    if (ParamValues constants = uniformChoices(method, perMaterial); constants != constantChoices_) {
        constantChoices_ = std::move(constants);
        variantChanged_ = true;
    }
    for (size_t i = 0; i < perMaterial.size(); ++i)
        if (!scene.materials[i].glinty) perMaterial[i].clear();   // the method's data ignore them
    if (methodResources_) methodResources_->setMaterials(perMaterial);
    if (rows.empty()) rows = shared;
    const GLsizeiptr bytes = GLsizeiptr(rows.size() * sizeof(float));
    if (bytes > materialMethodParamsBytes_) {
        materialMethodParams_ = gl::createBuffer(bytes, nullptr);
        materialMethodParamsBytes_ = bytes;
    }
    glNamedBufferSubData(materialMethodParams_.id(), 0, bytes, rows.data());
}

void LightingPass::prepare(PrepareContext& context) {
    const RenderSettings& settings = context.settings;
    // A coat appeared or went (a scene, a material override): the programs with or without its terms.
    if (const bool coated = sceneHasClearcoat(context.scene); coated != clearcoat_) {
        clearcoat_ = coated;
        variantChanged_ = true;
    }
    Environment& environment = context.environment;
    const IblMode& ibl = findIblMode(iblId_);
    // IBL-mode resources may render (per-object environment maps), so they update before this frame's state.
    if (iblResources_)
        iblResources_->prepare(settings.iblModeValues(iblId_), context.scene,
                               environment.enabled() ? environment.sourceCube() : 0, capture_);
    uploadMethodParams(context.scene, settings);
    if (variantChanged_) {   // the coat or the constant enumerations: one rebuild for both
        variantChanged_ = false;
        rebuildVariant();
    }
    std::vector<float> iblParams = packIblParams(ibl, settings.iblModeValues(ibl.id));
    glNamedBufferSubData(iblParams_.id(), 0, GLsizeiptr(iblParams.size() * sizeof(float)), iblParams.data());
    // On-demand data of the method and the IBL mode (tables, trees, the prefiltered environment of wang2020),
    // rebuilt when their parameters changed; what ran is listed in --stats and the window's edit line.
    if (!methodResources_ && !iblResources_) return;
    environment.bind(settings.value(param::env_intensity), settings.value(param::env_rotation));
    auto record = [&](const std::vector<std::pair<std::string, double>>& ran) {
        for (const auto& [name, ms] : ran) context.recordOnDemand(name, ms);
    };
    if (methodResources_) record(methodResources_->update(sharedMethodValues_));
    if (iblResources_ && environment.enabled())
        record(iblResources_->update(settings.iblModeValues(iblId_), methodResources_.get()));
}

void LightingPass::execute(const FrameContext& frame) {
    const bool split = frame.settings.value(param::lighting_split_glinty) > 0.5f && frame.settings.debugView == 0;
    if (split && !nonGlintyProgram_) buildSplitPrograms();
    const FrameImage& gbuffer = frame.resources.read(FrameResource::GBuffer);
    const GLuint depth = frame.resources.read(FrameResource::Depth).texture();
    const FrameImage& classes = frame.resources.write(FrameResource::ShadingClass);
    const FrameImage& hdr = frame.resources.write(FrameResource::Hdr);
    if (split) {
        // The classes: depth 1 on glinty pixels, 0 elsewhere (shaders/frame/lighting_class.frag).
        gl::PipelineState state = gl::fullscreenState(
            classFramebuffer_.get("shading class", {}, classes.texture(), {classes.serial}), frame.width, frame.height);
        state.depthTest = true;
        state.depthFunc = GL_ALWAYS;
        state.depthWrite = true;
        state.apply();
        classProgram_->use();
        glBindTextureUnit(UNIT_GBUFFER_DUVDY_MATERIAL, gbuffer.texture(1));
        glBindTextureUnit(UNIT_GBUFFER_DEPTH, depth);
        glBindVertexArray(frame.emptyVao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    // Location 0 the radiance, 1 the glint part (TAA), 2.. the method's own targets (absent ones: GL_NONE).
    const FrameImage& glintPart = frame.resources.write(FrameResource::GlintPart);
    const FrameImage& methodTargets = frame.resources.write(FrameResource::MethodTargets);
    std::vector<GLuint> colors = {hdr.texture(), frame.temporalAa ? glintPart.texture() : 0};
    colors.insert(colors.end(), methodTargets.textures.begin(), methodTargets.textures.end());
    while (colors.size() > 1 && colors.back() == 0) colors.pop_back();
    const GLuint framebuffer = framebuffer_.get("lighting", colors, classes.texture(),
                                                {hdr.serial, glintPart.serial, methodTargets.serial, classes.serial});
    gl::PipelineState state = gl::fullscreenState(framebuffer, frame.width, frame.height);
    if (frame.blendSample) {
        // Running mean: mean_k = estimate / (k + 1) + mean_{k-1} * k / (k + 1). Only the HDR target blends (the
        // method's targets hold this sample's glints; its passes add them with the same weight).
        state.blend = {true, 0, GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA, GL_CONSTANT_ALPHA,
                       GL_ONE_MINUS_CONSTANT_ALPHA, {0.0f, 0.0f, 0.0f, frame.blendWeight}};
    }
    if (split) {
        state.depthTest = true;
        state.depthFunc = GL_EQUAL;
        state.depthRange = {1.0f, 1.0f};   // the glinty class
    }
    state.apply();
    program_.use();
    bindInputs(frame);
    glBindVertexArray(frame.emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (!split) return;
    state.depthRange = {0.0f, 0.0f};       // the others, with the program that has no method code
    state.apply();
    nonGlintyProgram_->use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void LightingPass::bindInputs(const FrameContext& frame) {
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_METHOD_PARAMS, methodParams_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_MATERIAL_METHOD_PARAMS, materialMethodParams_.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_IBL_PARAMS, iblParams_.id());
    if (methodResources_) methodResources_->bind();
    if (iblResources_) iblResources_->bind();
    frame.environment.bind(frame.settings.value(param::env_intensity), frame.settings.value(param::env_rotation));
    bindProbeInputs(frame.resources.read(FrameResource::ReflectionProbes));
    bindEnvironmentGlints(frame.resources.read(FrameResource::EnvironmentGlints), noEnvironmentGlints_);
    ltcTable_.bind();   // the area lights' LTC tables (render/lights/)
    // Per-light visibility (shaders/shadows/shadows.glsl); without SHADOWS the program reads none.
    if (shadows_)
        bindShadowInputs(frame.resources.read(FrameResource::ShadowMaps), frame.resources.read(FrameResource::ShadowMask));
    const FrameImage& gbuffer = frame.resources.read(FrameResource::GBuffer);
    // Target 5 (the clear coat) and target 6 (the slope covariance, published only for methods that read it) sit
    // on units of their own.
    for (int i = 0; i < int(gbuffer.textures.size()); ++i)
        glBindTextureUnit(i == 5   ? GLuint(UNIT_GBUFFER_CLEARCOAT)
                          : i == 6 ? GLuint(UNIT_GBUFFER_SLOPE_COVARIANCE)
                                   : GLuint(UNIT_GBUFFER_FIRST + i),
                          gbuffer.texture(size_t(i)));
    glBindTextureUnit(UNIT_GBUFFER_DEPTH, frame.resources.read(FrameResource::Depth).texture());
    glBindTextureUnit(UNIT_AMBIENT_OCCLUSION, frame.resources.read(FrameResource::AmbientOcclusion).texture());
}

}  // namespace glimmer
