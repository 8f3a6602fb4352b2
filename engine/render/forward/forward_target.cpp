#include "render/forward/forward_target.h"

#include "core/error.h"
#include "environment/ibl/ibl_modes.h"

namespace glimmer {

GLuint ForwardTarget::framebuffer(const FrameImage& hdr, const FrameImage& depth) {
    return framebuffer_.get("forward", {hdr.texture()}, depth.texture(), {hdr.serial, depth.serial});
}

void ForwardTarget::saveOpaque(const FrameImage& hdr) {
    if (!saved_ || savedWidth_ != hdr.width || savedHeight_ != hdr.height) {
        saved_ = gl::createTexture2D(GL_RGBA32F, hdr.width, hdr.height);
        savedWidth_ = hdr.width;
        savedHeight_ = hdr.height;
    }
    glCopyImageSubData(hdr.texture(), GL_TEXTURE_2D, 0, 0, 0, 0, saved_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, hdr.width,
                       hdr.height, 1);
}

void ForwardTarget::restoreOpaque(const FrameImage& hdr) const {
    if (!saved_ || savedWidth_ != hdr.width || savedHeight_ != hdr.height) return;
    glCopyImageSubData(saved_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, hdr.texture(), GL_TEXTURE_2D, 0, 0, 0, 0, hdr.width,
                       hdr.height, 1);
}

FrameImage ForwardTarget::opaqueMean() const {
    if (!saved_) return {};
    return {.textures = {saved_.id()}, .width = savedWidth_, .height = savedHeight_};
}

bool forwardPassesRun(const FrameContext& frame) {
    return frame.settings.debugView == 0 && (frame.gpuScene.hasBlended() || frame.gpuScene.hasOpaqueEmissive());
}

bool ForwardAccumulationPass::runs(const FrameContext& frame) const {
    if (!forwardPassesRun(frame) || !findIblMode(frame.settings.ibl).accumulates) return false;
    return mode_ == Mode::Save || frame.blendSample;
}

void ForwardAccumulationPass::execute(const FrameContext& frame) {
    if (mode_ == Mode::Save) {
        target_->saveOpaque(frame.resources.read(FrameResource::Hdr));
        frame.resources.publish(FrameResource::OpaqueMean, target_->opaqueMean());
    } else {
        frame.resources.read(FrameResource::OpaqueMean);
        target_->restoreOpaque(frame.resources.write(FrameResource::Hdr));
    }
}

}  // namespace glimmer
