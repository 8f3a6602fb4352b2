#include "render/image/exposure_pass.h"

#include "common/bindings.glsl"

namespace glimmer {

namespace {
constexpr unsigned kBins = 256;   // HISTOGRAM_BINS of shaders/image/exposure_common.glsl
}

ExposurePass::ExposurePass(const std::filesystem::path& shaderRoot)
    : histogram_(shaderRoot, {"image/luminance_histogram", {{GL_COMPUTE_SHADER, "image/luminance_histogram.comp"}}}),
      adapt_(shaderRoot, {"image/exposure_adapt", {{GL_COMPUTE_SHADER, "image/exposure_adapt.comp"}}}) {
    std::vector<unsigned> zeros(kBins, 0u);
    histogramBins_ = gl::createBuffer(GLsizeiptr(kBins * sizeof(unsigned)), zeros.data());
    const float state[2] = {0.0f, 0.0f};
    state_ = gl::createBuffer(sizeof state, state);
}

bool ExposurePass::wanted(const RenderSettings& settings) {
    return settings.debugView == 0 && settings.value(param::exposure_auto) > 0.5f;
}

// The state only while auto exposure runs: the tone mapping applies none when the image is empty.
void ExposurePass::prepare(PrepareContext& context) {
    context.resources.publish(FrameResource::ExposureState,
                              wanted(context.settings) ? FrameImage{.buffer = state_.id()} : FrameImage{});
}

void ExposurePass::execute(const FrameContext& frame) {
    const FrameImage& hdr = frame.resources.read(FrameResource::PostHdr);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_EXPOSURE_HISTOGRAM, histogramBins_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_EXPOSURE_STATE, frame.resources.write(FrameResource::ExposureState).buffer);
    histogram_.use();
    // The post passes run at the post size (the output size under TAA upsampling).
    const int width = frame.postWidth, height = frame.postHeight;
    glBindTextureUnit(UNIT_EXPOSURE_HDR, hdr.texture());
    glProgramUniform2i(histogram_.id(), 0, width, height);
    glDispatchCompute(GLuint((width + 15) / 16), GLuint((height + 15) / 16), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    adapt_.use();
    glProgramUniform1f(adapt_.id(), 0, adaptation_);
    glProgramUniform1f(adapt_.id(), 1, kLowPercentile);
    glProgramUniform1f(adapt_.id(), 2, kHighPercentile);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

float ExposurePass::meteredEv() const {
    float state[2] = {0, 0};
    glGetNamedBufferSubData(state_.id(), 0, sizeof state, state);
    return state[0];
}
float ExposurePass::targetEv() const {
    float state[2] = {0, 0};
    glGetNamedBufferSubData(state_.id(), 0, sizeof state, state);
    return state[1];
}

}  // namespace glimmer
