// The environment's specular reflection by the facets of each glinty pixel (issue 36: "the environment by Monte
// Carlo over the map"). The radiance a pixel's facets reflect is
//
//   L_ref = int L(l) F G D_est(h) (v.h) / (n.v) dh = sum over facets i of (w_i c_i / rho)
//           x int L(l(h)) F G (v.h) / (n.v) x D(h) K(m_i; h) / P(h) dh
//
// (l the mirror direction of v about h; D_est as facet_estimator.h): every facet of the footprint is visited
// (exact), and the integral over its lobe is estimated with a few stratified half vectors inside it (the Monte
// Carlo part: the map is sampled where the facet reflects it). The renderer's IBL modes give glinty materials the
// smooth lobe; what the reference adds is L_ref - L_smooth, with L_smooth = int L F G D (v.h) / (n.v) dh
// estimated on the same map by stratified importance sampling of D(h) (h.n), times the pixel's ambient occlusion
// (as the lighting pass does with its environment term). Not modelled: the clear coat's attenuation of the
// base (the reference's environment glints are those of an uncoated surface) and reflection probes (the
// distant map only).
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "reference/discrete_facets/facet_image.h"
#include "environment/cube_texels.h"

namespace glimmer::facets {

// The environment as the lighting pass looks it up with envRadiance(d, 0): the source cube's level 0 (read back
// from the renderer), times env.intensity, turned by env.rotation about +y (0 for the procedural sky).
class EnvironmentMap {
public:
    EnvironmentMap(envref::CubeImage cube, double intensity, double rotationDegrees);
    glm::dvec3 radiance(const glm::dvec3& worldDirection) const;

private:
    envref::CubeImage cube_;
    double intensity_, rotationDegrees_;
};

struct EnvironmentOptions {
    int facetSamples = 4;     // half vectors per facet inside its lobe (stratified)
    int smoothSamples = 64;   // half vectors of the smooth estimate (a stratified square grid, rounded down)
};

// Per pixel (bottom-up, like `surface`): L_ref - L_smooth (rgb) on glinty pixels, 0 elsewhere.
std::vector<glm::vec3> environmentGlints(const SurfaceImage& surface, const std::vector<Material>& materials,
                                         const EnvironmentMap& map, const ReferenceOptions& options,
                                         const EnvironmentOptions& environment, double* seconds = nullptr);

}  // namespace glimmer::facets
