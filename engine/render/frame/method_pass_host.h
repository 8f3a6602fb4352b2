// A method's pass (GlintMethod::createPasses) run as a pass of the frame: it sees the frame through
// MethodPassFrame, so methods depend on nothing of the renderer. It reads the method's lighting targets and the
// depth and adds its result to the HDR radiance.
#pragma once
#include <memory>

#include "gl/handles.h"
#include "render/frame/pass.h"

namespace glimmer {

class MethodPassHost : public Pass {
public:
    explicit MethodPassHost(std::unique_ptr<MethodPass> pass) : pass_(std::move(pass)) {}
    const char* name() const override { return pass_->name(); }
    PassResources resources() const override {
        return {.reads = {FrameResource::MethodTargets, FrameResource::Depth}, .writes = {FrameResource::Hdr}};
    }
    std::vector<gl::Program*> programs() override { return pass_->programs(); }
    bool runs(const FrameContext& frame) const override { return pass_->runs(methodFrame(frame, 0)); }
    void execute(const FrameContext& frame) override {
        const FrameImage& hdr = frame.resources.write(FrameResource::Hdr);
        pass_->execute(methodFrame(frame, hdrFramebuffer_.get("method pass radiance", {hdr.texture()}, 0, {hdr.serial})));
    }

private:
    static MethodPassFrame methodFrame(const FrameContext& frame, GLuint hdrFramebuffer) {
        MethodPassFrame m;
        m.width = frame.width;
        m.height = frame.height;
        m.values = &frame.settings.methodValues(frame.settings.method);
        m.debugView = frame.settings.debugView;
        m.blendWeight = frame.blendWeight;
        m.hdrFramebuffer = hdrFramebuffer;
        const FrameImage& targets = frame.resources.read(FrameResource::MethodTargets);
        m.lightingTargets.assign(targets.textures.begin(), targets.textures.end());
        m.depth = frame.resources.read(FrameResource::Depth).texture();
        m.emptyVao = frame.emptyVao;
        return m;
    }
    std::unique_ptr<MethodPass> pass_;
    gl::AttachedFramebuffer hdrFramebuffer_;
};

}  // namespace glimmer
