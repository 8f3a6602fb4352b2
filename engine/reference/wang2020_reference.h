// CPU reference of the discrete stochastic microfacet model (Jakob et al. 2014; Wang et al. 2020 Sec. 3.1,
// Eq. 3-4) for one light: explicit particles (the positions the quadtree encodes, wang2020_quadtree.h) with
// explicit Beckmann normals, counting those inside the pixel footprint whose reflection of the light direction
// falls in the cone of half-angle gamma around the view direction. No DPF, no scales: the ground truth the
// shader (shaders/glints/wang2020/wang2020.glsl) is compared with.
#pragma once
#include <glm/glm.hpp>

#include "glints/wang2020/wang2020_dpf.h"
#include "glints/wang2020/wang2020_quadtree.h"

namespace glimmer::wang2020 {

struct ReferenceResult {
    float D = 0.0f;       // equivalent NDF value (same normalization as glintD, see the shader's header)
    int inFootprint = 0;  // particles in A
    int reflecting = 0;   // particles in A reflecting i into the cone around o
};

// wi, wo: unit directions in the shading frame (z = normal). gamma in radians.
ReferenceResult explicitParticleD(const Quadtree& tree, const Footprint& fp, glm::vec3 wi, glm::vec3 wo, float alpha,
                                  float gamma);

// Environment lighting by Monte Carlo over the explicit particles (Eq. 10 with Eq. 3-4): particle k in A reflects
// the environment around i_k = reflect(o, m_k) into the cone around o; over that cone (solid angle sigma(Omega_o))
// the radiance is taken constant, so L = 1/(N a(A)) sum_k L_i(i_k) M(i_k, o) with M = (i.m) G / ((m.n)(o.n))
// (Fresnel left to the caller, as in the shader). radiance(i) takes a shading-frame direction.
template <class Radiance>
glm::vec3 explicitParticleEnvironment(const Quadtree& tree, const Footprint& fp, glm::vec3 wo, float alpha,
                                      Radiance radiance);
float smithG1Beckmann(glm::vec3 w, float alpha);

// CPU version of the prefilter pass (shaders/glints/wang2020/wang2020_prefilter.comp) for an environment of constant radiance
// 1: (L^o, P^) of Eq. 16 (the same K = 64 points, cone form or the paper's DPF-weighted form) and Eq. 17 for a view
// direction wo in the normal's frame (with constant radiance the table does not depend on the normal). gamma in
// radians (the cone form's cone; the dpf table is already accumulated for it).
enum class PrefilterEstimator { Dpf = 0, Cone = 1 };  // as wang2020::Prefilter::Estimator
glm::vec2 prefilteredConstantEnvironment(const DpfTable& dpf, float alpha, float gamma, glm::vec3 wo,
                                         PrefilterEstimator estimator);

}  // namespace glimmer::wang2020

namespace glimmer::wang2020 {

template <class Radiance>
glm::vec3 explicitParticleEnvironment(const Quadtree& tree, const Footprint& fp, glm::vec3 wo, float alpha,
                                      Radiance radiance) {
    glm::dvec3 sum(0.0);
    if (wo.z <= 0.0f) return glm::vec3(0.0f);
    forEachParticle(tree, fp, alpha, [&](const Particle& p) {
        float om = glm::dot(wo, p.normal);
        if (om <= 0.0f) return;
        glm::vec3 wi = 2.0f * om * p.normal - wo;
        if (wi.z <= 0.0f) return;
        float G = smithG1Beckmann(wi, alpha) * smithG1Beckmann(wo, alpha);
        float M = om * G / (p.normal.z * wo.z);
        sum += glm::dvec3(radiance(wi)) * double(M);
    });
    double expected = tree.particles * fp.area();
    return expected > 0.0 ? glm::vec3(sum / expected) : glm::vec3(0.0f);
}

}  // namespace glimmer::wang2020
