#include "reference/clearcoat_reference.h"

#include <algorithm>
#include <cmath>

#include "reference/brdf_reference.h"

namespace glimmer::reference {

static double coatAlpha(const ClearcoatLayer& coat) { return std::max(coat.roughness * coat.roughness, 1e-3); }

double clearcoatWeight(const ClearcoatLayer& coat, double nDotV) {
    return std::clamp(coat.clearcoat, 0.0, 1.0) * schlickFresnel(glm::dvec3(0.04), std::abs(nDotV)).x;
}

double clearcoatLobeCosine(const ClearcoatLayer& coat, const glm::dvec3& wi, const glm::dvec3& wo) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;
    double alpha = coatAlpha(coat);
    glm::dvec3 h = glm::normalize(wi + wo);
    return ggxD(h, alpha) * ggxG1(wi, alpha) * ggxG1(wo, alpha) / (4.0 * wo.z);
}

glm::dvec3 shadeClearcoat(const ClearcoatLayer& coat, const glm::dvec3& base, const glm::dvec3& wi,
                          const glm::dvec3& wo, const glm::dvec3& irradiance, const glm::dvec3& ambient) {
    double w = clearcoatWeight(coat, wo.z);
    return base * (1.0 - w) + w * (clearcoatLobeCosine(coat, wi, wo) * irradiance + ambient);
}

}  // namespace glimmer::reference
