#include "render/frame/method_output_check.h"

#include <array>
#include <cstdio>

#include "common/bindings.glsl"

namespace glimmer {

namespace {
constexpr int kCounterCount = 8;   // layout of MethodOutputBlock (shaders/frame/method_output_check.glsl)
}

std::string MethodOutputCounts::describe(const std::string& method) const {
    std::string lines;
    auto add = [&](const std::string& line) { lines += (lines.empty() ? "" : "\n") + ("method '" + method + "': " + line); };
    if (nonFiniteD) add("glintD returned NaN or Inf " + std::to_string(nonFiniteD) + " times (those lights add nothing there)");
    if (negativeD) add("glintD returned a negative value " + std::to_string(negativeD) + " times (an NDF is never negative)");
    if (nonFiniteRadiance)
        add(std::to_string(nonFiniteRadiance) + " radiance values were NaN or Inf before the lighting pass zeroed them (black pixels)");
    if (negativeRadiance)
        add(std::to_string(negativeRadiance) + " radiance values were negative before the lighting pass clamped them to 0");
    if (implausible()) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "D exceeded 4 x the smooth NDF (+1) at %.0f%% of %llu sampled evaluations; an energy-conserving "
                      "method stays under 25%%: the radiance is implausible (glimmer check-method)",
                      100.0 * farAboveSmoothFraction(), (unsigned long long)sampledEvaluations);
        add(text);
    }
    return lines;
}

MethodOutputCheck::MethodOutputCheck() {
    std::array<uint32_t, kCounterCount> zero{};
    counters_ = gl::createBuffer(GLsizeiptr(sizeof zero), zero.data(), GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
}

void MethodOutputCheck::bind() const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_METHOD_OUTPUT, counters_.id()); }

void MethodOutputCheck::reset() {
    std::array<uint32_t, kCounterCount> zero{};
    glNamedBufferSubData(counters_.id(), 0, GLsizeiptr(sizeof zero), zero.data());
}

MethodOutputCounts MethodOutputCheck::read() const {
    std::array<uint32_t, kCounterCount> c{};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(counters_.id(), 0, GLsizeiptr(sizeof c), c.data());
    MethodOutputCounts counts;
    counts.sampledEvaluations = c[0];
    counts.sampledFarAboveSmooth = c[1];
    counts.nonFiniteD = c[2];
    counts.negativeD = c[3];
    counts.nonFiniteRadiance = c[4];
    counts.negativeRadiance = c[5];
    return counts;
}

}  // namespace glimmer
