// CPU reference of the discrete stochastic microfacet model (Jakob et al. 2014; Wang et al. 2020 Sec. 3.1,
// Eq. 3-4) for one light: explicit particles (the positions the quadtree encodes, wang2020_quadtree.h) with
// explicit Beckmann normals, counting those inside the pixel footprint whose reflection of the light direction
// falls in the cone of half-angle gamma around the view direction. No DPF, no scales: the ground truth the
// shader (shaders/glints/wang2020.glsl) is compared with.
#pragma once
#include <glm/glm.hpp>

#include "glints/wang2020_quadtree.h"

namespace glimmer::wang2020 {

struct ReferenceResult {
    float D = 0.0f;          // equivalent NDF value (same normalization as glintD, see the shader's header)
    int inFootprint = 0;     // particles in A
    int reflecting = 0;      // particles in A reflecting i into the cone around o
};

// wi, wo: unit directions in the shading frame (z = normal). gamma in radians.
ReferenceResult explicitParticleD(const Quadtree& tree, const Footprint& fp, glm::vec3 wi, glm::vec3 wo,
                                  float alpha, float gamma);

}  // namespace glimmer::wang2020
