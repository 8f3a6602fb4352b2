#include "glints/wang2020/wang2020_prefilter.h"
#include "common/bindings.glsl"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <vector>

#include "core/clock.h"

namespace glimmer::wang2020 {

PrefilterResolution prefilterResolution(float alpha) {
    auto dim = [&](int at01, int at05) {
        return std::clamp(int(std::lround(at01 * 0.1 / std::max(alpha, 1e-3f))), at05, at01);
    };
    return {dim(31, 10), dim(60, 18), dim(10, 4), dim(36, 12)};
}

Prefilter::Prefilter(const std::filesystem::path& shaderRoot) {
    gl::ProgramDesc desc;
    desc.name = "wang2020/prefilter";
    desc.stages = {{GL_COMPUTE_SHADER, "glints/wang2020/wang2020_prefilter.comp"}};
    program_ = gl::Program(shaderRoot, desc);
}

double Prefilter::run(GLuint dpfTexture, float alpha, float gamma, Estimator estimator, PrefilterResolution res) {
    Stopwatch clock;
    res_ = res;
    std::vector<glm::vec4> header = {glm::vec4(res.thetaN, res.phiN, res.thetaO, res.phiO)};
    header.resize(res.size() + 1, glm::vec4(0.0f));
    table_ = gl::createBuffer(GLsizeiptr(header.size() * sizeof(glm::vec4)), header.data(), 0);
    GLint previous = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &previous);  // the caller may be between use() and draw
    program_.use();
    glProgramUniform4i(program_.id(), glGetUniformLocation(program_.id(), "u_tableSize"), res.thetaN, res.phiN,
                       res.thetaO, res.phiO);
    glProgramUniform1f(program_.id(), glGetUniformLocation(program_.id(), "u_alpha"), alpha);
    glProgramUniform1f(program_.id(), glGetUniformLocation(program_.id(), "u_gamma"), gamma);
    glProgramUniform1i(program_.id(), glGetUniformLocation(program_.id(), "u_estimator"), int(estimator));
    glBindTextureUnit(UNIT_METHOD_FIRST, dpfTexture);   // u_wangDpf, as in the lighting pass
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTableBinding, table_.id());
    glDispatchCompute(GLuint((res.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glFinish();
    glUseProgram(GLuint(previous));
    return clock.elapsedMs();
}

std::vector<glm::vec4> Prefilter::read() const {
    std::vector<glm::vec4> out(res_.size());
    glGetNamedBufferSubData(table_.id(), sizeof(glm::vec4), GLsizeiptr(out.size() * sizeof(glm::vec4)), out.data());
    return out;
}

void Prefilter::bind() const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kTableBinding, table_.id()); }

}  // namespace glimmer::wang2020
