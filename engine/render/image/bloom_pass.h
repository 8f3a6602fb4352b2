// Bloom pass (shaders/image/bloom_*.frag; docs/image.md): a chain of half-size levels built with Jimenez's 13-tap
// filter (Karis average on the first step), then tent upsamples summed back to the top. Reads the HDR radiance
// (after TAA, FrameResource::PostHdr); writes its own levels, the first of which (FrameResource::Bloom, half the
// post size) ends with the sum of every level, which the tone-mapping pass mixes into the HDR image as
// Bloom * (1 / level count) with weight bloom.strength.
#pragma once
#include <filesystem>
#include <vector>

#include "gl/handles.h"
#include "render/frame/pass.h"

namespace glimmer {

class BloomPass : public Pass {
public:
    explicit BloomPass(const std::filesystem::path& shaderRoot);
    const char* name() const override { return "bloom"; }
    PassResources resources() const override { return {.reads = {FrameResource::PostHdr}, .writes = {FrameResource::Bloom}}; }
    std::vector<gl::Program*> programs() override { return {&downsample_, &upsample_}; }
    // Sizes the chain for the post size and publishes its result (an empty image when bloom is off: tone mapping
    // then adds none).
    void prepare(PrepareContext& context) override;
    // The final image with bloom.strength > 0 (AOVs are shown as they are).
    bool runs(const FrameContext& frame) const override { return wanted(frame.settings); }
    void execute(const FrameContext& frame) override;
    static bool wanted(const RenderSettings& settings);

    void resize(int width, int height);
    // The chain on `source` (width x height); execute() runs it on the HDR target. Sets all of its GL state.
    void apply(GLuint source, int width, int height, float radius, GLuint emptyVao);
    GLuint result() const { return levels_.empty() ? 0 : levels_[0].texture.id(); }
    int levelCount() const { return int(levels_.size()); }

    static constexpr int kMaxLevels = 6;   // 640x360: down to 10x6 texels, a blur radius of ~1/6 of the height

private:
    struct Level {
        int width = 0, height = 0;
        gl::Texture texture;
        gl::Framebuffer framebuffer;
    };
    gl::Program downsample_, upsample_;
    gl::Sampler linear_;
    std::vector<Level> levels_;
    int width_ = 0, height_ = 0;
};

}  // namespace glimmer
