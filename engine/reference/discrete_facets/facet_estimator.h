// The glint material's NDF at one pixel, counted on its realization (facet_realization.h): the facets of the
// pixel's UV footprint whose reflection lobe holds the half vector h, normalized so that the expectation over
// realizations is the smooth D(h) exactly:
//
//   D_est(h) = D(h) x S(h) / (rho x P(h)),   S(h) = sum over facets i of  w(uv_i) c_i K(m_i; h),
//
// with w the footprint's weight (integrating to 1 over UV), c_i the facet's colour, K its lobe (facet_realization.h
// Lobe), rho the facet density per unit UV and P(h) = int D(m) (m.n) K(m; h) dm the probability that one facet
// reflects h. E[S] = rho P(h), so E[D_est] = D(h). For the cone lobe P(h) = pi gamma^2 D(h) (h.n) (1 + O(gamma^2 /
// alpha^2)), the README's p; with the box footprint S x A is the number of reflecting facets, Poisson with mean
// lambda = rho A P(h), and D_est / D = count / lambda (README "The glint material").
#pragma once
#include <glm/glm.hpp>

#include "reference/discrete_facets/facet_realization.h"

namespace glimmer::facets {

// The pixel's filter over its UV footprint (the parallelogram uv + s duv/dx + t duv/dy, s, t in [-1/2, 1/2]):
//  Box: 1 / A inside the parallelogram (closed: a facet on its boundary belongs to it), A = |det(duv/dx, duv/dy)|.
//  Gaussian: the Gaussian of the same second moments (covariance J J^T / 12), truncated at Mahalanobis radius 3.5
//  and renormalized to the truncated mass.
enum class FootprintFilter { Box = 0, Gaussian = 1 };

struct PixelFootprint {
    glm::dvec2 uv{0.0}, duvdx{0.0}, duvdy{0.0};
};

struct FacetEstimate {
    glm::dvec3 d{0.0};      // D_est per colour channel
    double ratio = 0.0;     // D_est / D(h), the channels' mean
    double lambda = 0.0;    // expected reflecting facets: rho A P(h) (A the footprint's area)
    long facetsTested = 0;  // facets of the queried region whose lobe weight was evaluated
};

class FacetEstimator {
public:
    FacetEstimator(const FacetMaterial& material, FootprintFilter filter = FootprintFilter::Box);

    const FacetRealization& realization() const { return realization_; }
    const FacetMaterial& material() const { return realization_.material(); }
    FootprintFilter filter() const { return filter_; }

    // The smooth NDF D(h) (shading frame), as shaders/common/brdf.glsl.
    double smoothD(const glm::dvec3& h) const;
    // K(m; h): the lobe of a facet of normal m at half vector h (1 / 0 for the cone).
    double lobeWeight(const glm::dvec3& m, const glm::dvec3& h) const;
    // P(h) = int D(m) (m.n) K(m; h) dm by quadrature over the lobe (Gauss-Legendre in the angle from h,
    // trapezoid in the azimuth around it: errors below 1e-6 relative for gamma <= alpha).
    double lobeProbability(const glm::dvec3& h) const;
    // Solid angle of the lobe, int K(m; h) dm (the same quadrature).
    double lobeSolidAngle(const glm::dvec3& h) const;

    // The footprint's weight at `uv` (integrates to 1), 0 outside; and a UV box that holds its support.
    double footprintWeight(const PixelFootprint& fp, const glm::dvec2& uv) const;
    bool footprintBounds(const PixelFootprint& fp, glm::dvec2& lo, glm::dvec2& hi) const;
    static double footprintArea(const PixelFootprint& fp);

    // D_est(h) at one pixel; `densityScale` multiplies rho in the normalization (a density mask read at the
    // pixel, as the methods read it; 1 = none). Every facet of the footprint's region whose lobe can reach h is
    // visited and weighed exactly. A degenerate footprint (zero area) or h below the surface gives 0.
    FacetEstimate estimate(const PixelFootprint& fp, const glm::dvec3& h) const;

    // Calls visit(facet, weight) for every facet of the footprint (all normals): environment lighting.
    template <class Visit> void forEachFootprintFacet(const PixelFootprint& fp, Visit&& visit) const;

private:
    FacetRealization realization_;
    FootprintFilter filter_;
    double truncatedMass_ = 1.0;
    template <class Integrand> double lobeIntegral(const glm::dvec3& h, Integrand&& integrand) const;
};

template <class Visit> void FacetEstimator::forEachFootprintFacet(const PixelFootprint& fp, Visit&& visit) const {
    FacetRegion region;   // every normal
    if (!footprintBounds(fp, region.uvMin, region.uvMax)) return;
    realization_.forEach(region, [&](const Facet& f) {
        double w = footprintWeight(fp, f.uv);
        if (w > 0.0) visit(f, w);
    });
}

}  // namespace glimmer::facets
