// Lights of a size in the discrete-facet reference (issue 37: "the statistics against the physical discrete-facet
// reference under the same area light"): rect, disk and sphere lights, point and spot lights of a radius, and the
// sun of its angular diameter. The light reflected by a pixel's facets is
//
//   N = int over the light's directions l of D_est(h(l)) dl
//     = sum over facets i of (w_i c_i / rho) int K(m_i; h) D(h) / P(h) [l(h) hits the light] 4 (v.h) dh
//
// (dl = 4 (v.h) dh, the mirror's Jacobian; D_est as facet_estimator.h). Every facet of the footprint whose lobe can
// reach a half vector of the light is visited (exact culling by a cone that bounds the light's half vectors); the
// integral over its lobe is taken with stratified half vectors inside it, each tested against the light's shape
// (exact wherever the lobe lies wholly inside or outside the light; Monte Carlo only across the light's edge). A
// light smaller than the directions one facet reflects (the sun, a far sphere) is sampled the other way round:
// stratified directions over the light, D_est counted exactly at each (the facets whose lobe holds its h).
// Its expectation over realizations is M = int over the light of D(h(l)) dl, computed on the same shape with
// stratified directions in the cone that bounds the light. The renderer multiplies the smooth specular of the
// light (its LTC integral, or the punctual evaluation at the centre for the sun) by D_est / D at the centre
// direction, so the reference uploads D_est = (N / M) x D(h_centre): the light's glint factor N / M, expectation 1.
// Assumed, as by the renderer's glint factor: the emitted radiance, Fresnel and masking do not vary across the
// light (they cancel in N / M).
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "reference/discrete_facets/facet_estimator.h"
#include "scene/scene.h"

namespace glimmer::facets {

// A light's extent as seen from shaded points (world space). Punctual lights (point and spot of radius 0) have none.
struct LightShape {
    enum Kind { None, Cone, Sphere, Rect, Disk } kind = None;
    glm::dvec3 centre{0.0}, direction{0.0, 1.0, 0.0};   // Cone: direction towards the light; Rect, Disk: front normal
    glm::dvec3 right{1.0, 0.0, 0.0}, up{0.0, 0.0, 1.0};   // Rect: the width and height axes
    double halfWidth = 0.0, halfHeight = 0.0, radius = 0.0, cosHalfAngle = 1.0;
    bool twoSided = false;

    // Whether the ray from `position` along unit `direction` meets the light (its emitting side).
    bool hits(const glm::dvec3& position, const glm::dvec3& rayDirection) const;
    // A cone (unit axis, half-angle in radians) that holds every direction from `position` to the light.
    void boundingCone(const glm::dvec3& position, glm::dvec3& axis, double& halfAngle) const;
};
LightShape lightShape(const Light& light);

struct ExtendedLightOptions {
    int facetSamples = 16;    // half vectors per facet lobe, or directions over a small light (4 x 4 stratified)
    int lightSamples = 1024;  // directions for M (a 32 x 32 stratified grid)
};

struct ExtendedEstimate {
    glm::dvec3 factor{0.0};   // N / M per colour channel (0 where the light is wholly below the horizon)
    double expected = 0.0;    // M, int over the light of D(h(l)) dl (shading frame, above the horizon)
    double lambda = 0.0;      // rho A int over the light's half vectors of D(h) (h.n) dh: facets that see it
    long facetsTested = 0;
};

// N / M at one pixel: v the unit direction to the eye and n, t, b the shading frame (world), `position` the
// shaded point, all world space. Deterministic for a seed.
ExtendedEstimate estimateOverLight(const FacetEstimator& estimator, const PixelFootprint& footprint,
                                   const glm::dvec3& position, const glm::dvec3& n, const glm::dvec3& t,
                                   const glm::dvec3& b, const glm::dvec3& v, const LightShape& light,
                                   const ExtendedLightOptions& options, uint64_t seed);

}  // namespace glimmer::facets
