// The target of the forward passes after lighting (emissive, transparent): the HDR radiance with the G-buffer's
// depth attached, so forward draws are depth-tested against the opaque surfaces (no depth writes).
//
// Accumulating IBL modes blend each sample's opaque radiance into a running mean held in the HDR target; a
// composite (a * S + (1 - a) * L) is not linear in that mean, so it must not be folded into it. The opaque mean
// is therefore saved before the forward passes draw and restored before the next sample's lighting pass blends
// into it (ForwardAccumulationPass): every sample then shows the composite over the exact opaque mean.
#pragma once
#include <memory>

#include "gl/handles.h"
#include "render/frame/pass.h"

namespace glimmer {

// The forward passes' shared state (one feature, several passes): their framebuffer over the frame's HDR radiance
// and depth, and the saved opaque mean (FrameResource::OpaqueMean, owned here).
class ForwardTarget {
public:
    // The framebuffer (HDR colour + G-buffer depth), rebuilt when either was reallocated.
    GLuint framebuffer(const FrameImage& hdr, const FrameImage& depth);
    // Copies of the HDR target (the opaque mean) for accumulation.
    void saveOpaque(const FrameImage& hdr);
    void restoreOpaque(const FrameImage& hdr) const;
    FrameImage opaqueMean() const;

private:
    gl::AttachedFramebuffer framebuffer_;
    gl::Texture saved_;
    int savedWidth_ = 0, savedHeight_ = 0;
};

// True when the frame shows radiance (not an AOV) and the scene has something for the forward passes.
bool forwardPassesRun(const FrameContext& frame);

// "forward_save" after the method passes, "forward_restore" before the lighting pass of a later sample: only with
// an accumulating IBL mode (FrameContext::blendSample on later samples) and a scene with forward content.
class ForwardAccumulationPass : public Pass {
public:
    enum class Mode { Save, Restore };
    ForwardAccumulationPass(std::shared_ptr<ForwardTarget> target, Mode mode) : target_(std::move(target)), mode_(mode) {}
    const char* name() const override { return mode_ == Mode::Save ? "forward_save" : "forward_restore"; }
    PassResources resources() const override {
        if (mode_ == Mode::Save) return {.reads = {FrameResource::Hdr}, .writes = {FrameResource::OpaqueMean}};
        return {.writes = {FrameResource::Hdr}, .readsPrevious = {FrameResource::OpaqueMean}};
    }
    std::vector<gl::Program*> programs() override { return {}; }
    bool runs(const FrameContext& frame) const override;
    void execute(const FrameContext& frame) override;

private:
    std::shared_ptr<ForwardTarget> target_;
    Mode mode_;
};

}  // namespace glimmer
