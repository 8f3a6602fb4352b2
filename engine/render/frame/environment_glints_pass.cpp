#include "render/frame/environment_glints_pass.h"

#include <vector>

#include "common/bindings.glsl"
#include "environment/ibl/ibl_modes.h"
#include "glints/methods.h"

namespace glimmer {

void EnvironmentGlintsPass::prepare(PrepareContext& context) {
    const IblMode& ibl = findIblMode(context.settings.ibl);
    const EnvironmentGlintSettings settings = environmentGlintSettings(ibl, context.settings.iblModeValues(ibl.id));
    const bool active = findGlintMethod(context.settings.method).environmentGlints && settings.levels > 0 &&
                        context.environment.enabled();
    // Not built yet and the frame's refinements are spent (the window's first picture takes none): this frame has
    // no environment glints.
    if (!active || (!glints_.built() && !context.refinements.take("environment glints"))) {
        context.resources.publish(FrameResource::EnvironmentGlints, {});
        return;
    }
    // The probes as ProbesPass published them this frame: a new capture is a new array (a new serial); the count
    // is its layers / 12 (2 NDFs x 6 faces per probe). Width 0: none (the empty zero array).
    const FrameImage& probes = context.resources.get(FrameResource::ReflectionProbes);
    EnvironmentGlints::Probes probeData;
    if (GLuint array = probes.texture(); array && probes.width > 0) {
        GLint layerFaces = 0;
        glGetTextureLevelParameteriv(array, 0, GL_TEXTURE_DEPTH, &layerFaces);
        probeData = {array, int(layerFaces) / 12, int(probes.serial)};
    }
    for (const auto& [name, ms] : glints_.update(settings, context.environment.sourceCube(), Environment::kFaceSize,
                                                 context.environment.key(), probeData, true))
        context.recordOnDemand(name, ms);
    context.resources.publish(FrameResource::EnvironmentGlints,
                              {.textures = {glints_.environmentWeights(), glints_.probeWeights()},
                               .buffer = glints_.levelBlock(),
                               .width = EnvironmentGlints::kFaceSize,
                               .height = EnvironmentGlints::kFaceSize,
                               .levels = EnvironmentGlints::kLevels});
}

NoEnvironmentGlints::NoEnvironmentGlints() {
    std::vector<unsigned char> zero(64, 0);   // EnvGlintBlock's header: info.x = 0 levels
    block = gl::createBuffer(GLsizeiptr(zero.size()), zero.data(), 0);
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &id);
    glTextureStorage3D(id, 1, GL_RGBA32F, 1, 1, 6);
    empty = gl::Texture(id);
}

void bindEnvironmentGlints(const FrameImage& glints, const NoEnvironmentGlints& none) {
    const bool any = glints.buffer != 0;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_ENV_GLINTS, any ? glints.buffer : none.block.id());
    glBindTextureUnit(UNIT_ENV_GLINT_WEIGHTS, any ? glints.texture(0) : none.empty.id());
    glBindTextureUnit(UNIT_PROBE_GLINT_WEIGHTS, any && glints.texture(1) ? glints.texture(1) : none.empty.id());
}

}  // namespace glimmer
