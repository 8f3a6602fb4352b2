#include "render/image/bloom_pass.h"

#include <algorithm>

#include "gl/pipeline_state.h"
#include "gl/samplers.h"
#include "common/bindings.glsl"

namespace glimmer {

BloomPass::BloomPass(const std::filesystem::path& shaderRoot)
    : downsample_(shaderRoot, {"image/bloom_downsample",
                               {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                {GL_FRAGMENT_SHADER, "image/bloom_downsample.frag"}}}),
      upsample_(shaderRoot, {"image/bloom_upsample",
                             {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "image/bloom_upsample.frag"}}}) {
    linear_ = gl::createLinearClampSampler();
}

bool BloomPass::wanted(const RenderSettings& settings) {
    return settings.debugView == 0 && settings.value(param::bloom_strength) > 0.0f;
}

void BloomPass::resize(int width, int height) {
    if (width == width_ && height == height_) return;
    width_ = width;
    height_ = height;
    levels_.clear();
    int w = width, h = height;
    while (int(levels_.size()) < kMaxLevels && std::min(w, h) >= 4) {
        w = std::max(1, w / 2);
        h = std::max(1, h / 2);
        Level level;
        level.width = w;
        level.height = h;
        // Half floats suffice after the Karis average (a firefly is divided by 1 + its luminance).
        level.texture = gl::createTexture2D(GL_RGBA16F, w, h);
        glTextureParameteri(level.texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);   // the tone-mapping pass's taps
        glTextureParameteri(level.texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(level.texture.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(level.texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        level.framebuffer = gl::createFramebuffer("bloom level", {level.texture.id()});
        levels_.push_back(std::move(level));
    }
}

void BloomPass::prepare(PrepareContext& context) {
    if (!wanted(context.settings)) {
        context.resources.publish(FrameResource::Bloom, {});
        return;
    }
    resize(context.view.postWidth, context.view.postHeight);
    // The first level's size; the tone mapping divides the sum by the level count.
    context.resources.publish(FrameResource::Bloom,
                              levels_.empty() ? FrameImage{}
                                              : FrameImage{.textures = {levels_[0].texture.id()},
                                                           .width = levels_[0].width,
                                                           .height = levels_[0].height,
                                                           .levels = int(levels_.size())});
}

void BloomPass::execute(const FrameContext& frame) {
    frame.resources.write(FrameResource::Bloom);
    apply(frame.resources.read(FrameResource::PostHdr).texture(), frame.postWidth, frame.postHeight,
          frame.settings.value(param::bloom_radius), frame.emptyVao);
}

void BloomPass::apply(GLuint source, int width, int height, float radius, GLuint emptyVao) {
    resize(width, height);
    if (levels_.empty()) return;
    glBindVertexArray(emptyVao);
    // The HDR target is read with GL_NEAREST by the other passes; bilinear taps need a sampler of their own.
    glBindSampler(UNIT_BLOOM_SOURCE, linear_.id());

    downsample_.use();
    int sourceWidth = width, sourceHeight = height;
    for (size_t i = 0; i < levels_.size(); ++i) {
        gl::fullscreenState(levels_[i].framebuffer.id(), levels_[i].width, levels_[i].height).apply();
        glBindTextureUnit(UNIT_BLOOM_SOURCE, source);
        glProgramUniform2f(downsample_.id(), 0, 1.0f / float(sourceWidth), 1.0f / float(sourceHeight));
        glProgramUniform1i(downsample_.id(), 1, i == 0 ? 1 : 0);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        source = levels_[i].texture.id();
        sourceWidth = levels_[i].width;
        sourceHeight = levels_[i].height;
    }

    // Coarse to fine: level i += tent(level i + 1), so level 0 ends with the sum of all levels.
    upsample_.use();
    glProgramUniform1f(upsample_.id(), 1, radius);
    for (size_t i = levels_.size() - 1; i-- > 0;) {
        gl::PipelineState state = gl::fullscreenState(levels_[i].framebuffer.id(), levels_[i].width, levels_[i].height);
        state.blend = {true, -1, GL_ONE, GL_ONE, GL_ONE, GL_ONE, glm::vec4(0.0f)};
        state.apply();
        glBindTextureUnit(UNIT_BLOOM_SOURCE, levels_[i + 1].texture.id());
        glProgramUniform2f(upsample_.id(), 0, 1.0f / float(levels_[i + 1].width), 1.0f / float(levels_[i + 1].height));
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glBindSampler(UNIT_BLOOM_SOURCE, 0);
}

}  // namespace glimmer
