// Shadow-mask pass (shaders/shadows/shadow_mask.frag): the visibility of every shadowed light (shadows/shadows.glsl: view
// selection, bias, PCF) at every ShadowMaps::maskStep()-th G-buffer pixel, into ShadowMaps' RGBA8 mask array, one
// channel per light, one draw per four lights. The lighting pass reads it back with a plane-aware 2 x 2
// interpolation (at half resolution) or one texel per layer, instead of filtering every light's map inside its light
// loop; at half resolution (shadow.half_res, the window's default on software renderers) the lookups run at a
// quarter of the pixels (docs/shadows.md#cost).
// Each layer draws with a program compiled for the filters of its four slots (ShadowMaps::maskLayerFilters):
// llvmpipe runs both sides of every branch, so one generic program paid for every kind of lookup at every light
// (docs/shadows.md#cost). The variants are built when a new combination first appears and kept.
// State: no depth test, no blending, viewport = the mask's size.
#pragma once
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "render/frame/pass.h"
#include "render/shadows/shadow_maps.h"

namespace glimmer {

class ShadowMaskPass : public Pass {
public:
    ShadowMaskPass(const std::filesystem::path& shaderRoot, std::shared_ptr<ShadowMaps> shadows);
    const char* name() const override { return "shadow_mask"; }
    PassResources resources() const override {
        return {.reads = {FrameResource::ShadowMaps, FrameResource::GBuffer, FrameResource::Depth},
                .writes = {FrameResource::ShadowMask}};
    }
    std::vector<gl::Program*> programs() override;
    // Allocates the mask for this frame's size and shadowed-light count and publishes it.
    void prepare(PrepareContext& context) override;
    // With shadows on, except on later samples of an accumulated view (same G-buffer: the mask is still valid).
    bool runs(const FrameContext& frame) const override;
    void execute(const FrameContext& frame) override;

private:
    // The program for `filters` (one SHADOW_FILTER_* per slot), built on first use.
    gl::Program& programFor(const glm::ivec4& filters);

    std::filesystem::path shaderRoot_;
    std::map<std::string, std::unique_ptr<gl::Program>> programs_;   // by their SHADOW_MASK_FILTERS value
    std::shared_ptr<ShadowMaps> shadows_;
};

}  // namespace glimmer
