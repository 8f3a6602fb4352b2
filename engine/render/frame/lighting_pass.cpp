#include "render/frame/lighting_pass.h"

#include "gl/pipeline_state.h"
#include "common/bindings.glsl"
#include "render/probes/reflection_probes.h"
#include "render/shadows/shadow_maps.h"

namespace glimmer {

gl::ProgramDesc lightingProgramDesc(const std::string& methodId, const std::string& iblId, bool shadows,
                                    bool nonGlinty) {
    const GlintMethod& method = findGlintMethod(methodId);
    const IblMode& ibl = findIblMode(iblId);
    checkIblModeMethod(ibl, method.id);
    gl::ProgramDesc desc;
    desc.name = "lighting/" + method.id + (ibl.id == "prefiltered" ? "" : "/" + ibl.id);
    desc.stages = {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "frame/lighting.frag"}};
    desc.defines = {method.define, ibl.define};
    if (method.glintPostPass) desc.defines.push_back("GLINT_POST_PASS");
    if (shadows) desc.defines.push_back("SHADOWS");
    if (nonGlinty) {
        static const std::string nonGlintyDefine = "NON_GLINTY_PIXELS";   // (a named string: GCC 12's -Warray-bounds
        desc.defines.push_back(nonGlintyDefine);                          // misfires on the literal's temporary)
        desc.name += "/non-glinty";
    }
    desc.preamble = methodParamsGlsl(method, true) + iblParamsGlsl(ibl);
    desc.includeMacros["GLINT_METHOD_FILE"] = method.shaderFile;
    desc.includeMacros["IBL_MODE_FILE"] = ibl.shaderFile;
    return desc;
}

LightingPass::LightingPass(const std::filesystem::path& shaderRoot, const std::string& methodId,
                           const std::string& iblId, bool shadows)
    : shaderRoot_(shaderRoot),
      methodId_(methodId),
      iblId_(iblId),
      program_(shaderRoot, lightingProgramDesc(methodId, iblId, shadows)),
      shadows_(shadows) {}

std::vector<gl::Program*> LightingPass::programs() {
    std::vector<gl::Program*> all{&program_};
    if (nonGlintyProgram_) all.push_back(nonGlintyProgram_.get());
    if (classProgram_) all.push_back(classProgram_.get());
    return all;
}

void LightingPass::buildSplitPrograms() {
    nonGlintyProgram_ = std::make_unique<gl::Program>(shaderRoot_, lightingProgramDesc(methodId_, iblId_, shadows_, true));
    classProgram_ = std::make_unique<gl::Program>(
        shaderRoot_, gl::ProgramDesc{"lighting class", {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                                        {GL_FRAGMENT_SHADER, "frame/lighting_class.frag"}}});
}

void LightingPass::execute(const FrameContext& frame) {
    const bool split = frame.settings.common_("lighting.split_glinty") > 0.5f && frame.settings.debugView == 0;
    if (split && !nonGlintyProgram_) buildSplitPrograms();
    if (split) {
        // The classes: depth 1 on glinty pixels, 0 elsewhere (shaders/frame/lighting_class.frag).
        gl::PipelineState classes = gl::fullscreenState(frame.targets.shadingClassFramebuffer(), frame.width,
                                                        frame.height);
        classes.depthTest = true;
        classes.depthFunc = GL_ALWAYS;
        classes.depthWrite = true;
        classes.apply();
        classProgram_->use();
        glBindTextureUnit(UNIT_GBUFFER_DUVDY_MATERIAL, frame.targets.gbufferTexture(1));
        glBindTextureUnit(UNIT_GBUFFER_DEPTH, frame.targets.depthTexture());
        glBindVertexArray(frame.emptyVao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    const bool glintTargets = findGlintMethod(frame.settings.method).glintPostPass;
    gl::PipelineState state = gl::fullscreenState(glintTargets       ? frame.targets.lightingGlintFramebuffer()
                                                  : frame.temporalAa ? frame.targets.lightingGlintPartFramebuffer()
                                                                     : frame.targets.hdrFramebuffer(),
                                                  frame.width, frame.height);
    if (frame.blendSample) {
        // Running mean: mean_k = estimate / (k + 1) + mean_{k-1} * k / (k + 1). Only the HDR target blends (the
        // glint targets hold this sample's glints; the method's post pass adds them with the same weight).
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
    if (frame.methodResources) frame.methodResources->bind();
    if (frame.iblResources) frame.iblResources->bind();
    frame.environment.bind(frame.settings.common_("env.intensity"), frame.settings.common_("env.rotation"));
    if (frame.probes) frame.probes->bind(frame.probesActive);
    if (shadows_) frame.shadows->bind();   // per-light visibility (common/shadows.glsl)
    for (int i = 0; i < FrameTargets::kGBufferColorCount; ++i)
        glBindTextureUnit(i == 5 ? GLuint(UNIT_GBUFFER_CLEARCOAT) : GLuint(UNIT_GBUFFER_FIRST + i),
                          frame.targets.gbufferTexture(i));
    glBindTextureUnit(UNIT_GBUFFER_DEPTH, frame.targets.depthTexture());
    if (!frame.ambientOcclusion && !unoccluded_) unoccluded_ = gl::createConstantTexture(1.0f, 1.0f, 1.0f, 1.0f);
    glBindTextureUnit(UNIT_AMBIENT_OCCLUSION, frame.ambientOcclusion ? frame.ambientOcclusion : unoccluded_.id());
}

}  // namespace glimmer
