#include "glints/wang2020/wang2020_post_pass.h"

#include <memory>
#include <string>

#include "core/error.h"
#include "gl/pipeline_state.h"

namespace glimmer::glintpost {

int radiusOf(int taps) { return taps < 1 ? 0 : (taps - 1) / 2; }

std::vector<float> binomialWeights(int radius) {
    if (radius < 0 || radius > kMaxRadius)
        throw Error("glint post pass: blur radius " + std::to_string(radius) + " outside 0.." +
                    std::to_string(kMaxRadius));
    // Row 2r of Pascal's triangle in doubles (C(30, 15) ~ 1.6e8 is exact), divided by 4^r.
    std::vector<double> row(size_t(2 * radius + 1), 0.0);
    row[0] = 1.0;
    for (int n = 1; n <= 2 * radius; ++n)
        for (int k = n; k > 0; --k) row[size_t(k)] += row[size_t(k - 1)];
    double total = 0.0;
    for (double c : row) total += c;
    std::vector<float> weights(size_t(radius + 1));
    for (int k = 0; k <= radius; ++k) weights[size_t(k)] = float(row[size_t(radius + k)] / total);
    return weights;
}
namespace {

// The intermediates of the two blurs, at the frame's size: the occlusion blur's horizontal sums (RG32F: sum of
// w m v, sum of w m) and its result (RGBA32F: occluded glints, blurred visibility), which the glint blur reads.
struct PostTargets {
    int width = 0, height = 0;
    gl::Texture occlusionSums, occludedGlint;
    gl::Framebuffer occlusionSumsFbo, occludedGlintFbo;

    void resize(int w, int h) {
        if (w == width && h == height) return;
        width = w;
        height = h;
        occlusionSums = gl::createTexture2D(GL_RG32F, w, h);
        occludedGlint = gl::createTexture2D(GL_RGBA32F, w, h);
        occlusionSumsFbo = gl::createFramebuffer("occlusion sums", {occlusionSums.id()});
        occludedGlintFbo = gl::createFramebuffer("occluded glints", {occludedGlint.id()});
    }
};

int tapsOf(const MethodPassFrame& frame, const char* name) {
    for (const ParamSpec& spec : findGlintMethod("wang2020").params)
        if (spec.name == name) return int(paramOr(*frame.values, spec) + 0.5f);
    throw Error(std::string("wang2020: glint post pass needs the parameter ") + name);
}

void setKernel(const gl::Program& program, int radius) {
    std::vector<float> weights = binomialWeights(radius);
    glProgramUniform1i(program.id(), 1, radius);
    glProgramUniform1fv(program.id(), 2, GLsizei(weights.size()), weights.data());
}

gl::Program fullscreenProgram(const std::filesystem::path& root, const std::string& name) {
    return gl::Program(root, {name, {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "glints/wang2020/wang2020_" + name + ".frag"}}});
}

// Debug views have no glints to add.
class OcclusionBlurPass : public MethodPass {
public:
    OcclusionBlurPass(const std::filesystem::path& root, std::shared_ptr<PostTargets> targets)
        : program_(fullscreenProgram(root, "glint_occlusion_blur")), targets_(std::move(targets)) {}
    const char* name() const override { return "glint_occlusion_blur"; }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    bool runs(const MethodPassFrame& frame) const override { return frame.debugView == 0; }
    void execute(const MethodPassFrame& frame) override {
        targets_->resize(frame.width, frame.height);
        program_.use();
        setKernel(program_, radiusOf(tapsOf(frame, "blur_occlusion")));
        glBindTextureUnit(0, frame.lightingTargets.at(0));   // wang2020Method()'s lightingTargets, in order
        glBindTextureUnit(1, frame.lightingTargets.at(1));
        glBindVertexArray(frame.emptyVao);
        gl::fullscreenState(targets_->occlusionSumsFbo.id(), frame.width, frame.height).apply();
        glProgramUniform1i(program_.id(), 0, 0);   // u_pass 0: sums along x
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindTextureUnit(2, targets_->occlusionSums.id());
        gl::fullscreenState(targets_->occludedGlintFbo.id(), frame.width, frame.height).apply();
        glProgramUniform1i(program_.id(), 0, 1);   // u_pass 1: along y, divide, multiply, add the light glints
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

private:
    gl::Program program_;
    std::shared_ptr<PostTargets> targets_;
};

class GlintBlurPass : public MethodPass {
public:
    GlintBlurPass(const std::filesystem::path& root, std::shared_ptr<PostTargets> targets)
        : program_(fullscreenProgram(root, "glint_blur")), targets_(std::move(targets)) {}
    const char* name() const override { return "glint_blur"; }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    bool runs(const MethodPassFrame& frame) const override { return frame.debugView == 0; }
    void execute(const MethodPassFrame& frame) override {
        program_.use();
        setKernel(program_, radiusOf(tapsOf(frame, "blur_glints")));
        glBindTextureUnit(0, targets_->occludedGlint.id());
        glBindVertexArray(frame.emptyVao);
        // Added with this frame's weight (a running mean for accumulating IBL modes); HDR alpha kept.
        gl::PipelineState state = gl::fullscreenState(frame.hdrFramebuffer, frame.width, frame.height);
        state.blend = {true, -1, GL_CONSTANT_ALPHA, GL_ONE, GL_ZERO, GL_ONE, {0.0f, 0.0f, 0.0f, frame.blendWeight}};
        state.apply();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

private:
    gl::Program program_;
    std::shared_ptr<PostTargets> targets_;
};

}  // namespace

MethodPassList createPasses(const std::filesystem::path& shaderRoot) {
    auto targets = std::make_shared<PostTargets>();
    MethodPassList passes;
    passes.push_back(std::make_unique<OcclusionBlurPass>(shaderRoot, targets));
    passes.push_back(std::make_unique<GlintBlurPass>(shaderRoot, targets));
    return passes;
}

}  // namespace glimmer::glintpost
