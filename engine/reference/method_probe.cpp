#include "reference/method_probe.h"
#include "common/bindings.glsl"

#include "core/files.h"
#include "gl/handles.h"
#include "render/shader_interface.h"

namespace glimmer {

GlintMethodProbe::GlintMethodProbe(const std::string& methodId, const ParamValues& values,
                                   const std::filesystem::path& shaderRoot)
    : method_(findGlintMethod(methodId)), values_(values) {
    gl::ProgramDesc desc;
    desc.name = "probe/" + method_.id;
    desc.stages = {{GL_COMPUTE_SHADER, "reference/method_probe.comp"}};
    desc.defines = {method_.define};
    desc.preamble = methodParamsGlsl(method_);
    desc.includeMacros["GLINT_METHOD_FILE"] = method_.shaderFile;
    program_ = gl::Program(shaderRoot.empty() ? defaultShaderDir() : shaderRoot, desc);
    if (method_.createResources) resources_ = method_.createResources();
}

GlintMethodProbe::~GlintMethodProbe() = default;

std::vector<GlintProbeOutput> GlintMethodProbe::run(const std::vector<GlintProbeInput>& inputs) {
    if (inputs.empty()) return {};
    std::vector<glm::vec4> packed;
    packed.reserve(inputs.size() * 3);
    for (const GlintProbeInput& in : inputs) {
        packed.emplace_back(in.uv, in.duvdx);
        packed.emplace_back(in.duvdy, in.alpha, float(in.ndf));
        packed.emplace_back(in.h, in.densityScale);
    }
    std::vector<float> params = packMethodParams(method_, values_);
    gl::Buffer paramBuffer = gl::createBuffer(GLsizeiptr(params.size() * sizeof(float)), params.data(), 0);
    gl::Buffer inBuffer = gl::createBuffer(GLsizeiptr(packed.size() * sizeof(glm::vec4)), packed.data(), 0);
    gl::Buffer outBuffer = gl::createBuffer(GLsizeiptr(packed.size() * sizeof(glm::vec4)), nullptr, 0);
    // A frame for methods that read it: identity camera at the origin, a 1 x 1 viewport.
    FrameUniforms frame{};
    frame.view = frame.projection = frame.viewProjection = frame.inverseViewProjection = glm::mat4(1.0f);
    frame.viewport = {1, 1, 0, 0};
    gl::Buffer frameBuffer = gl::createBuffer(GLsizeiptr(sizeof(frame)), &frame, 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_FRAME, frameBuffer.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_METHOD_PARAMS, paramBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_METHOD_LAST - 1, inBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_METHOD_LAST, outBuffer.id());
    if (resources_) {
        resources_->update(values_);
        resources_->bind();
    }
    program_.use();
    glDispatchCompute(GLuint((inputs.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> out(packed.size());
    glGetNamedBufferSubData(outBuffer.id(), 0, GLsizeiptr(out.size() * sizeof(glm::vec4)), out.data());
    std::vector<GlintProbeOutput> result(inputs.size());
    for (size_t i = 0; i < inputs.size(); ++i)
        result[i] = {out[3 * i].x, out[3 * i].y, out[3 * i + 1], out[3 * i + 2]};
    return result;
}

}  // namespace glimmer
