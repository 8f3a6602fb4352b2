// GTAO pass (shaders/ao/gtao.frag; Jimenez et al. 2016, Sec. 4): reads the G-buffer depth and normals, writes the
// raw screen-space visibility (AmbientOcclusion::rawTexture) at the internal resolution. Runs when ao.enabled and
// ao.screen are on; skipped, like the G-buffer, on later samples of an accumulated view. Its prepare() readies
// the AO feature for the frame (AmbientOcclusion::prepare: targets, and the sky-visibility bake of a new scene).
#pragma once
#include <filesystem>
#include <memory>

#include "render/ao/ambient_occlusion.h"
#include "render/frame/pass.h"

namespace glimmer {

class GtaoPass : public Pass {
public:
    GtaoPass(const std::filesystem::path& shaderRoot, std::shared_ptr<AmbientOcclusion> ao);
    ~GtaoPass() override;
    GtaoPass(const GtaoPass&) = delete;
    GtaoPass& operator=(const GtaoPass&) = delete;
    const char* name() const override { return "gtao"; }
    PassResources resources() const override {
        return {.reads = {FrameResource::GBuffer, FrameResource::Depth}, .writes = {FrameResource::AmbientOcclusionRaw}};
    }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    void prepare(PrepareContext& context) override;
    bool runs(const FrameContext& frame) const override;
    void execute(const FrameContext& frame) override;

private:
    gl::Program program_;
    std::shared_ptr<AmbientOcclusion> ao_;
    gl::Sampler linearDepthSampler_;   // bilinear depth at fractional sample positions (shaders/ao/gtao.frag)
};

}  // namespace glimmer
