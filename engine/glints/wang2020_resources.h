// GPU data of Wang et al. 2020 (shaders/glints/wang2020.glsl): the DPF table accumulated for the material's
// roughness and gamma (3D texture, unit 8) and the particle quadtree (SSBO, binding 8). update() re-runs only the
// passes a parameter change needs (Sec. 4.5): N, depth or seed -> quadtree; roughness or gamma -> DPF extraction
// + accumulation; anything else -> nothing.
#pragma once
#include "common/bindings.glsl"
#include <memory>

#include "gl/handles.h"
#include "glints/methods.h"
#include "glints/wang2020_dpf.h"
#include "glints/wang2020_quadtree.h"

namespace glimmer {

class Wang2020Resources : public GlintMethodResources {
public:
    static constexpr int kDpfUnit = UNIT_METHOD_FIRST;
    static constexpr int kQuadtreeBinding = BINDING_METHOD_FIRST;
    std::vector<std::pair<std::string, double>> update(const ParamValues& values) override;
    void bind() override;
    // For the IBL mode's prefilter pass (Sec. 4.4): the accumulated DPF and what it was built for.
    GLuint dpfTexture() const { return dpf_.id(); }
    float roughness() const { return roughness_; }
    float gamma() const { return gamma_; }
    uint64_t dpfVersion() const { return dpfVersion_; }

private:
    float roughness_ = -1, gamma_ = -1, particles_ = -1, depth_ = -1, seed_ = -1, tableScale_ = -1;
    std::shared_ptr<const wang2020::DpfSet> dpfSet_;
    gl::Texture dpf_;
    gl::Buffer quadtree_;
    uint64_t dpfVersion_ = 0;
};

std::unique_ptr<GlintMethodResources> createWang2020Resources();

}  // namespace glimmer
