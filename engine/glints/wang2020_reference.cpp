#include "glints/wang2020_reference.h"

#include <algorithm>
#include <cmath>

#include "glints/wang2020_dpf.h"

namespace glimmer::wang2020 {

ReferenceResult explicitParticleD(const Quadtree& tree, const Footprint& fp, glm::vec3 wi, glm::vec3 wo,
                                  float alpha, float gamma) {
    ReferenceResult r;
    float cosGamma = std::cos(gamma);
    forEachParticle(tree, fp, alpha, [&](const Particle& p) {
        ++r.inFootprint;
        float im = glm::dot(wi, p.normal);
        if (im <= 0.0f) return;  // the particle faces away from the light
        glm::vec3 reflected = 2.0f * im * p.normal - wi;
        if (glm::dot(reflected, wo) >= cosGamma) ++r.reflecting;  // Eq. 4: 1_Omega(h_k) 1_A(x_k)
    });
    glm::vec3 h = glm::normalize(wi + wo);
    double expected = tree.particles * fp.area();
    if (expected <= 0.0 || h.z <= 1e-4f) return r;
    // Eq. 3 with D^ = reflecting / N, expressed as the D that Cook-Torrance's D G F / (4 cos cos) expects.
    r.D = float(4.0 * glm::dot(wi, h) * r.reflecting / (expected * coneSolidAngle(gamma) * h.z));
    return r;
}

float smithG1Beckmann(glm::vec3 w, float alpha) {
    if (w.z <= 0.0f) return 0.0f;
    float tanTheta = std::sqrt(std::max(0.0f, 1.0f - w.z * w.z)) / w.z;
    if (tanTheta <= 0.0f) return 1.0f;
    float a = 1.0f / (alpha * tanTheta);
    if (a >= 1.6f) return 1.0f;
    return (3.535f * a + 2.181f * a * a) / (1.0f + 2.276f * a + 2.577f * a * a);
}

}  // namespace glimmer::wang2020
