#include "render/image/tonemap_pass.h"

#include "common/bindings.glsl"
#include "gl/pipeline_state.h"

namespace glimmer {

TonemapPass::TonemapPass(const std::filesystem::path& shaderRoot)
    : program_(shaderRoot, {"tonemap", {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "image/tonemap.frag"}}}) {
    const float none[2] = {0.0f, 0.0f};   // metered and target EV 0: what the shader reads without auto exposure
    noExposure_ = gl::createBuffer(sizeof none, none);
}

void TonemapPass::prepare(PrepareContext& context) {
    const View& view = context.view;
    if (!display_ || width_ != view.postWidth || height_ != view.postHeight) {
        width_ = view.postWidth;
        height_ = view.postHeight;
        display_ = gl::createTexture2D(GL_RGBA8, width_, height_);
        framebuffer_ = gl::createFramebuffer("display", {display_.id()});
    }
    context.resources.publish(FrameResource::Display, {.textures = {display_.id()}, .width = width_, .height = height_});
}

void TonemapPass::execute(const FrameContext& frame) {
    const GLuint hdr = frame.resources.read(FrameResource::PostHdr).texture();
    const FrameImage& bloom = frame.resources.read(FrameResource::Bloom);
    const FrameImage& exposure = frame.resources.read(FrameResource::ExposureState);
    gl::fullscreenState(framebuffer_.id(), width_, height_).apply();
    program_.use();
    const bool withBloom = bloom.texture() != 0;
    glBindTextureUnit(UNIT_TONEMAP_HDR, hdr);
    glBindTextureUnit(UNIT_TONEMAP_BLOOM, withBloom ? bloom.texture() : hdr);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_EXPOSURE_STATE, exposure.buffer ? exposure.buffer : noExposure_.id());
    glProgramUniform1i(program_.id(), 0, int(frame.settings.value(param::tonemap)));
    glProgramUniform1f(program_.id(), 1, withBloom ? frame.settings.value(param::bloom_strength) : 0.0f);
    glProgramUniform1i(program_.id(), 2, exposure.buffer != 0 ? 1 : 0);
    glProgramUniform1f(program_.id(), 3, withBloom ? 1.0f / float(bloom.levels) : 0.0f);
    glBindVertexArray(frame.emptyVao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace glimmer
