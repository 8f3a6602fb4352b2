// CPU reference of KHR_materials_clearcoat's layering as the lighting pass evaluates it (shaders/common/
// clearcoat.glsl), in double precision: coated = base * (1 - c Fc) + c Fc * coat lobe, Fc = Schlick(0.04, n_c.v).
#pragma once
#include <glm/glm.hpp>

namespace glimmer::reference {

struct ClearcoatLayer {
    double clearcoat = 0.0;    // intensity in [0, 1]
    double roughness = 0.0;    // perceptual: alpha = roughness^2 (floored at 1e-3 like the shader)
};

// The coat's share c Fc of the reflected light for n_c.v = nDotV.
double clearcoatWeight(const ClearcoatLayer& coat, double nDotV);

// The coat lobe without Fresnel times n_c.l: D_GGX G / (4 n_c.v), for unit vectors in the coat's shading frame
// (z = coat normal); 0 below the horizon.
double clearcoatLobeCosine(const ClearcoatLayer& coat, const glm::dvec3& wi, const glm::dvec3& wo);

// Coated radiance towards wo from a directional light of irradiance `irradiance` from wi and the constant ambient
// `ambient` (the coat reflects it with albedo 1, as lighting.frag does without an environment), given the base's
// radiance `base` for the same light and ambient (for example reference::shadeDirectional). Coat frame = base frame.
glm::dvec3 shadeClearcoat(const ClearcoatLayer& coat, const glm::dvec3& base, const glm::dvec3& wi,
                          const glm::dvec3& wo, const glm::dvec3& irradiance, const glm::dvec3& ambient);

}  // namespace glimmer::reference
