// Shadow-map pass: renders the depth of the views ShadowMaps::prepare marked dirty (render/shadows/shadow_maps.h), one
// layer each, culling the scene's chunks against the view's own frustum. Two instances run before the G-buffer:
// `shadow_sun` (the cascades of directional lights) and `shadow_point` (the cube faces of point lights and the
// views of spot lights). On a frame where nothing moved no view is dirty and the pass draws nothing.
// Two draws per view: the materials without an alpha mask, then the masked ones (their own program).
// State: depth test GREATER and writes (reversed Z, cleared to 0), no colour target, no blending, back faces of
// single-sided materials culled (GpuScene), slope-scaled polygon offset away from the light (shadow.slope_bias).
// The three shadow passes (sun, point, mask) share one ShadowMaps, the feature's state; the sun pass's prepare()
// fits every light's views for this frame (it comes first in the frame list) and publishes the maps.
#pragma once
#include <filesystem>
#include <memory>

#include "render/frame/pass.h"
#include "render/shadows/shadow_maps.h"

namespace glimmer {

class ShadowMapPass : public Pass {
public:
    ShadowMapPass(const std::filesystem::path& shaderRoot, ShadowArray array, std::shared_ptr<ShadowMaps> shadows);
    const char* name() const override { return array_ == ShadowArray::Sun ? "shadow_sun" : "shadow_point"; }
    PassResources resources() const override { return {.writes = {FrameResource::ShadowMaps}}; }
    std::vector<gl::Program*> programs() override { return {&unmasked_, &masked_}; }
    void prepare(PrepareContext& context) override;
    // Whenever a light of this kind has a shadow (so --stats lists the pass with ~0 ms on cached frames), except
    // on later samples of an accumulated view (same camera: nothing to re-render).
    bool runs(const FrameContext& frame) const override;
    void execute(const FrameContext& frame) override;

private:
    // Materials without an alpha mask: no fragment work, so the depth test runs before the (empty) fragment stage
    // (llvmpipe, court's first frame: sun cascades 468-574 -> 112-123 ms, cube faces 413-502 -> 126-129 ms; the
    // masked program draws nothing in a scene without masks). Alpha-masked materials
    // (glTF MASK): the texture read and discard.
    gl::Program unmasked_, masked_;
    ShadowArray array_;
    std::shared_ptr<ShadowMaps> shadows_;
};

}  // namespace glimmer
