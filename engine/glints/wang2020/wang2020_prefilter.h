// Wang et al. 2020, Sec. 4.2 / 4.4: the environment prefilter pass (shaders/glints/wang2020/wang2020_prefilter.comp) into
// the 4D glint table over normal and view direction: per entry rgb = filtered glint radiance L^o(n, o) (Eq. 16,
// K = 64), a = filtered DPF P^(n, o) (Eq. 17). Resolutions from roughness as in the paper's Table 2.
// Two estimators of Eq. 16 (header of the shader): the paper's (default) and a cone form (ours, optional).
#pragma once
#include "common/bindings.glsl"
#include <filesystem>
#include <glm/glm.hpp>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"

namespace glimmer::wang2020 {

struct PrefilterResolution {
    int thetaN = 10, phiN = 18, thetaO = 4, phiO = 12;
    size_t size() const { return size_t(thetaN) * phiN * thetaO * phiO; }
};
// Table 2: alpha 0.1 -> 31 x 60 x 10 x 36, alpha 0.5 -> 10 x 18 x 4 x 12. Between and beyond, each dimension scales
// with 1 / alpha, clamped to those two (our interpolation: the paper lists only these two).
PrefilterResolution prefilterResolution(float alpha);

class Prefilter {
public:
    static constexpr int kTableBinding = BINDING_IBL_FIRST;  // SSBO read by shaders/environment/ibl/wang2020.glsl
    explicit Prefilter(const std::filesystem::path& shaderRoot);
    enum class Estimator { Dpf = 0, Cone = 1 };
    // Runs the pass (environment bound at units 6-7 and binding 7, DPF at unit 8); returns its wall time (ms).
    // gamma in radians.
    double run(GLuint dpfTexture, float alpha, float gamma, Estimator estimator, PrefilterResolution res);
    void bind() const;
    std::vector<glm::vec4> read() const;  // for tests: the table without its header entry
    const PrefilterResolution& resolution() const { return res_; }
    size_t bytes() const { return (res_.size() + 1) * 16; }

private:
    gl::Program program_;
    gl::Buffer table_;
    PrefilterResolution res_;
};

}  // namespace glimmer::wang2020
