// Temporal anti-aliasing pass (docs/image.md): owns the jitter sequence, the history (non-glint and glint
// radiance, ping-pong) and the cut detection. Reads the HDR radiance, the glint part the lighting pass wrote
// (FrameTargets::glintPartTexture) and the depth; writes the resolved radiance into FrameTargets::postHdrTexture
// (and its history). The history has the post size (the output size): at the render size the plain resolve runs
// (shaders/image/taa_resolve.frag), below it the upsampling resolve (TAAU, shaders/image/taa_upsample.frag), so a
// change of render scale keeps the history (it is reprojected like camera motion) and only a change of the output
// size, a cut or an edit resets it. The renderer calls beginFrame() before the G-buffer pass, when TAA runs, to
// get this frame's jitter.
#pragma once
#include <filesystem>

#include <glm/glm.hpp>

#include "gl/handles.h"
#include "render/frame/pass.h"

namespace glimmer {

class TaaPass : public Pass {
public:
    explicit TaaPass(const std::filesystem::path& shaderRoot);
    const char* name() const override { return "taa"; }
    std::vector<gl::Program*> programs() override { return {&program_, &upsample_}; }
    bool runs(const FrameContext& frame) const override { return frame.temporalAa; }
    void execute(const FrameContext& frame) override;

    // Whether a frame with these settings runs TAA: aa=taa, the final image (AOVs stay unjittered), and an IBL mode
    // that does not accumulate (its later samples reuse sample 0's G-buffer).
    static bool wanted(const RenderSettings& settings);
    // Forgets the history: the next frame is unjittered and resolves to itself.
    void reset() {
        if (framesSinceReset_ != 0) ++resets_;
        framesSinceReset_ = 0;
    }
    // Starts a frame rendered at width x height and resolved at outputWidth x outputHeight (>= the render size):
    // resets on a change of the output size or a camera cut; returns this frame's jitter in render pixels.
    glm::vec2 beginFrame(const glm::mat4& unjitteredViewProjection, glm::vec3 cameraPosition, glm::vec3 forward,
                         int width, int height, int outputWidth, int outputHeight);
    unsigned framesSinceReset() const { return framesSinceReset_; }
    // Resets counted since construction (tests: a render-scale change must not reset).
    unsigned resets() const { return resets_; }
    void resize(int width, int height);

    // Reconstruction kernel width of the upsampling resolve, in output pixels (measured: docs/image.md).
    static constexpr float kUpsampleKernelWidth = 1.0f;

private:
    gl::Program program_, upsample_;
    int width_ = 0, height_ = 0;   // history (output) size
    unsigned resets_ = 0;
    glm::vec2 jitter_{0.0f};
    unsigned framesSinceReset_ = 0;
    int current_ = 0;   // ping-pong index of the history written this frame
    glm::mat4 viewProjection_{1.0f}, previousViewProjection_{1.0f};
    glm::vec3 previousPosition_{0.0f}, previousForward_{0.0f, 0.0f, -1.0f};
    gl::Texture resolved_, historyBase_[2], historyGlint_[2];
    gl::Framebuffer resolveFbo_[2];
    gl::Sampler linearClamp_;
};

}  // namespace glimmer
