#include "render/forward/forward_target.h"

#include "core/error.h"
#include "environment/ibl/ibl_modes.h"

namespace glimmer {

GLuint ForwardTarget::framebuffer(const FrameTargets& targets) {
    if (!fbo_ || hdr_ != targets.hdrTexture() || depth_ != targets.depthTexture() || width_ != targets.width() ||
        height_ != targets.height()) {
        fbo_ = gl::createFramebuffer("forward", {targets.hdrTexture()}, targets.depthTexture());
        hdr_ = targets.hdrTexture();
        depth_ = targets.depthTexture();
        width_ = targets.width();
        height_ = targets.height();
    }
    return fbo_.id();
}

void ForwardTarget::saveOpaque(const FrameTargets& targets) {
    if (!saved_ || savedWidth_ != targets.width() || savedHeight_ != targets.height()) {
        saved_ = gl::createTexture2D(GL_RGBA32F, targets.width(), targets.height());
        savedWidth_ = targets.width();
        savedHeight_ = targets.height();
    }
    glCopyImageSubData(targets.hdrTexture(), GL_TEXTURE_2D, 0, 0, 0, 0, saved_.id(), GL_TEXTURE_2D, 0, 0, 0, 0,
                       targets.width(), targets.height(), 1);
}

void ForwardTarget::restoreOpaque(const FrameTargets& targets) const {
    if (!saved_ || savedWidth_ != targets.width() || savedHeight_ != targets.height()) return;
    glCopyImageSubData(saved_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, targets.hdrTexture(), GL_TEXTURE_2D, 0, 0, 0, 0,
                       targets.width(), targets.height(), 1);
}

bool forwardPassesRun(const FrameContext& frame) {
    return frame.settings.debugView == 0 && (frame.gpuScene.hasBlended() || frame.gpuScene.hasOpaqueEmissive());
}

bool ForwardAccumulationPass::runs(const FrameContext& frame) const {
    if (!forwardPassesRun(frame) || !findIblMode(frame.settings.ibl).accumulates) return false;
    return mode_ == Mode::Save || frame.blendSample;
}

void ForwardAccumulationPass::execute(const FrameContext& frame) {
    if (mode_ == Mode::Save) target_->saveOpaque(frame.targets);
    else target_->restoreOpaque(frame.targets);
}

}  // namespace glimmer
