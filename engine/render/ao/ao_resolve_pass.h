// AO resolve pass (shaders/ao/ao_resolve.frag): the GTAO spatial denoiser (4 x 4 bilateral), times the baked sky
// visibility, raised to ao.power, with the multi-bounce fit (Jimenez et al. 2016, Sec. 5). Writes the factor the
// lighting pass applies to the environment / ambient term (AmbientOcclusion::occlusionTexture).
#pragma once
#include <filesystem>
#include <memory>

#include "render/ao/ambient_occlusion.h"
#include "render/frame/pass.h"

namespace glimmer {

class AoResolvePass : public Pass {
public:
    AoResolvePass(const std::filesystem::path& shaderRoot, std::shared_ptr<AmbientOcclusion> ao);
    const char* name() const override { return "ao_resolve"; }
    PassResources resources() const override {
        return {.reads = {FrameResource::GBuffer, FrameResource::Depth, FrameResource::AmbientOcclusionRaw},
                .writes = {FrameResource::AmbientOcclusion}};
    }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    // Publishes what the lighting pass reads: the resolved factor, or 1 x 1 white with ao.enabled = 0.
    void prepare(PrepareContext& context) override;
    bool runs(const FrameContext& frame) const override { return ao_->settings().enabled && !frame.blendSample; }
    void execute(const FrameContext& frame) override;

private:
    gl::Program program_;
    std::shared_ptr<AmbientOcclusion> ao_;
};

}  // namespace glimmer
