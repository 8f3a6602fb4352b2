// Runs a glint method's shader code (glintSetup + glintD, footprint and extra AOVs) on synthetic surfaces through
// a compute shader (shaders/reference/method_probe.comp), so tests and check-method (checks/method_checks.h) can
// check the real GLSL of any method, built-in or user, with controlled footprints and half vectors. Needs a
// current GL 4.5 context.
#pragma once
#include <glm/glm.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "core/params.h"
#include "gl/program.h"
#include "glints/methods.h"

namespace glimmer {

struct GlintProbeInput {
    glm::vec2 uv{0.0f}, duvdx{1e-3f, 0.0f}, duvdy{0.0f, 1e-3f};
    glm::vec3 h{0.0f, 0.0f, 1.0f};   // shading frame (z = normal); normalized by the probe
    float alpha = 0.3f;
    int ndf = 0;                     // 0 GGX, 1 Beckmann
    float densityScale = 1.0f;
};

struct GlintProbeOutput {
    float D = 0.0f;           // glintD
    float smoothD = 0.0f;     // D_smooth(h)
    glm::vec4 footprint{0.0f};
    glm::vec4 extra{0.0f};
};

class GlintMethodProbe {
public:
    GlintMethodProbe(const std::string& methodId, const ParamValues& values,
                     const std::filesystem::path& shaderRoot = {});
    ~GlintMethodProbe();
    std::vector<GlintProbeOutput> run(const std::vector<GlintProbeInput>& inputs);

private:
    GlintMethod method_;   // a copy: registering a user method may move the table's entries
    ParamValues values_;
    gl::Program program_;
    std::unique_ptr<GlintMethodResources> resources_;
};

}  // namespace glimmer
