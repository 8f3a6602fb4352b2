// Temporal anti-aliasing pass (docs/image.md): owns the jitter sequence, the history (non-glint and glint
// radiance, ping-pong), the cut detection, the glint part target (FrameResource::GlintPart, which the lighting pass
// writes) and the post HDR target (FrameResource::PostHdr). Reads the HDR radiance, the glint part and the depth;
// writes the resolved radiance into PostHdr (and its history). The history has the post size (the output size): at
// the render size the plain resolve runs (shaders/image/taa_resolve.frag), below it the upsampling resolve (TAAU,
// shaders/image/taa_upsample.frag), so a change of render scale keeps the history (it is reprojected like camera
// motion) and only a change of the output size, a cut or an edit resets it. Its prepare() decides whether the view
// is jittered, sets the view's jitter and post size, and publishes its targets.
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
    PassResources resources() const override {
        return {.reads = {FrameResource::Hdr, FrameResource::GlintPart, FrameResource::Depth},
                .writes = {FrameResource::PostHdr}};
    }
    std::vector<gl::Program*> programs() override { return {&program_, &upsample_}; }
    void prepare(PrepareContext& context) override;
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
    unsigned framesSinceReset() const { return framesSinceReset_; }
    // Resets counted since construction (tests: a render-scale change must not reset).
    unsigned resets() const { return resets_; }

    // Reconstruction kernel width of the upsampling resolve, in output pixels (measured: docs/image.md).
    static constexpr float kUpsampleKernelWidth = 1.0f;
    // A still camera (the unjittered view equals the last frame's) accumulates the plain mean of its frames, without
    // rectification or the feedback floor, and after one whole jitter cycle keeps the history as it is: a still
    // image. With the floor the history followed each jittered frame with weight taa.feedback (glints:
    // taa.glint_feedback) and glinty pixels changed by more than 10% between frames (issue 39; docs/image.md
    // "A still camera"). Moving again, the usual resolve resumes at once.
    bool converged() const { return stillIndex_ > unsigned(phases_); }
    unsigned stillFrames() const { return stillIndex_; }

private:
    // Starts a frame rendered at width x height and resolved at outputWidth x outputHeight (>= the render size):
    // resets on a change of the output size or a camera cut; returns this frame's jitter in render pixels.
    glm::vec2 beginFrame(const glm::mat4& unjitteredViewProjection, glm::vec3 cameraPosition, glm::vec3 forward,
                         int width, int height, int outputWidth, int outputHeight);
    void resizeHistory(int width, int height);

    gl::Program program_, upsample_;
    gl::Texture glintPart_, postHdr_;
    int glintPartWidth_ = 0, glintPartHeight_ = 0, postWidth_ = 0, postHeight_ = 0;
    int width_ = 0, height_ = 0;   // history (output) size
    unsigned resets_ = 0;
    glm::vec2 jitter_{0.0f};
    unsigned framesSinceReset_ = 0;
    unsigned stillIndex_ = 0;   // k-th consecutive frame with the same unjittered view (0: moved, reset)
    int phases_ = 16;           // jitter cycle of the current upscale ratio
    int current_ = 0;   // ping-pong index of the history written this frame
    glm::mat4 viewProjection_{1.0f}, previousViewProjection_{1.0f};
    glm::vec3 previousPosition_{0.0f}, previousForward_{0.0f, 0.0f, -1.0f};
    gl::Texture resolved_, historyBase_[2], historyGlint_[2];
    gl::Framebuffer resolveFbo_[2];
    gl::Sampler linearClamp_;
};

}  // namespace glimmer
