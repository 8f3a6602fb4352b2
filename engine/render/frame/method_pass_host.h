// A method's pass (GlintMethod::createPasses) run as a pass of the frame: it sees the frame through
// MethodPassFrame, so methods depend on nothing of the renderer.
#pragma once
#include <memory>

#include "render/frame/pass.h"

namespace glimmer {

class MethodPassHost : public Pass {
public:
    explicit MethodPassHost(std::unique_ptr<MethodPass> pass) : pass_(std::move(pass)) {}
    const char* name() const override { return pass_->name(); }
    std::vector<gl::Program*> programs() override { return pass_->programs(); }
    bool runs(const FrameContext& frame) const override { return pass_->runs(methodFrame(frame)); }
    void execute(const FrameContext& frame) override { pass_->execute(methodFrame(frame)); }

private:
    static MethodPassFrame methodFrame(const FrameContext& frame) {
        MethodPassFrame m;
        m.width = frame.width;
        m.height = frame.height;
        m.values = &frame.settings.methodValues(frame.settings.method);
        m.debugView = frame.settings.debugView;
        m.blendWeight = frame.blendWeight;
        m.hdrFramebuffer = frame.targets.hdrFramebuffer();
        m.glintEnvironment = frame.targets.glintEnvironmentTexture();
        m.glintLights = frame.targets.glintLightsTexture();
        m.depth = frame.targets.depthTexture();
        m.emptyVao = frame.emptyVao;
        return m;
    }
    std::unique_ptr<MethodPass> pass_;
};

}  // namespace glimmer
