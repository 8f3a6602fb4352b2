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

#include <algorithm>
#include <cmath>
#include <mutex>
#include <vector>

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

    // K(m; h), the lobe of a facet of normal m at half vector h, set up once per h. With x, y the components of m
    // along the lobe's axes around h (the tangent projected off h, and h x it) and e^2 = x^2 / a + a y^2 (a the
    // anisotropy; sin^2 of the angle to h when a = 1): the cone holds e <= sin(gamma), the Gaussian is
    // exp(-e^2 / (2 sigma^2)) up to e = 4 sigma; only m within 90 degrees of h.
    struct LobeTest {
        glm::dvec3 h{0.0, 0.0, 1.0}, t{1.0, 0.0, 0.0}, b{0.0, 1.0, 0.0};
        double anisotropy = 1.0, cosGamma = 1.0, reach2 = 0.0, inverseTwoSigma2 = 0.0;
        bool cone = true;
        double weight(const glm::dvec3& m) const {
            const double c = m.x * h.x + m.y * h.y + m.z * h.z;
            if (c <= 0.0) return 0.0;
            if (cone && anisotropy == 1.0) return c >= cosGamma ? 1.0 : 0.0;
            double e2;
            if (anisotropy == 1.0) {
                e2 = std::max(0.0, 1.0 - c * c);
            } else {
                const double x = m.x * t.x + m.y * t.y + m.z * t.z, y = m.x * b.x + m.y * b.y + m.z * b.z;
                e2 = x * x / anisotropy + anisotropy * y * y;
            }
            if (e2 > reach2) return 0.0;
            return cone ? 1.0 : std::exp(-e2 * inverseTwoSigma2);
        }
    };
    LobeTest lobeTest(const glm::dvec3& h) const;
    double lobeWeight(const glm::dvec3& m, const glm::dvec3& h) const { return lobeTest(h).weight(m); }
    // P(h) = int D(m) (m.n) K(m; h) dm by quadrature over the lobe (Gauss-Legendre in the angle from h,
    // trapezoid in the azimuth around it: errors below 1e-6 relative for gamma <= alpha).
    double lobeProbability(const glm::dvec3& h) const;
    // Solid angle of the lobe, int K(m; h) dm (the same quadrature).
    double lobeSolidAngle(const glm::dvec3& h) const;
    // P(h) / (D(h) (h.n)) from a table over h's polar angle (and azimuth when anisotropic), built on first use
    // (512 polar nodes, 64 azimuths when anisotropic), used by estimate() and the environment's many half vectors
    // (environment_glints.h). Within 1e-4 of the quadrature (tested).
    double lobeRatio(const glm::dvec3& h) const;

    // The footprint's filter, set up once per pixel: weight(uv) integrates to 1 over UV, 0 outside; lo / hi bound
    // its support (valid is false for a degenerate footprint).
    struct FootprintTest {
        bool valid = false, box = true;
        glm::dvec2 centre{0.0}, lo{0.0}, hi{0.0};
        double m00 = 0, m01 = 0, m10 = 0, m11 = 0;   // box: inverse Jacobian; Gaussian: inverse covariance (m01 = m10)
        double edge = 0.5, reach2 = 0.0, scale = 0.0; // box: |s|, |t| <= edge, weight scale; Gaussian: q <= reach2
        double weight(const glm::dvec2& uv) const {
            const double dx = uv.x - centre.x, dy = uv.y - centre.y;
            if (box) {
                const double s = m00 * dx + m01 * dy, t = m10 * dx + m11 * dy;
                return std::abs(s) <= edge && std::abs(t) <= edge ? scale : 0.0;
            }
            const double q = m00 * dx * dx + 2.0 * m01 * dx * dy + m11 * dy * dy;
            return q <= reach2 ? scale * std::exp(-0.5 * q) : 0.0;
        }
    };
    FootprintTest footprintTest(const PixelFootprint& fp) const;
    double footprintWeight(const PixelFootprint& fp, const glm::dvec2& uv) const {
        FootprintTest test = footprintTest(fp);
        return test.valid ? test.weight(uv) : 0.0;
    }
    bool footprintBounds(const PixelFootprint& fp, glm::dvec2& lo, glm::dvec2& hi) const;
    static double footprintArea(const PixelFootprint& fp);

    // D_est(h) at one pixel; `densityScale` multiplies rho in the normalization (a density mask read at the
    // pixel, as the methods read it; 1 = none). Every facet of the footprint's region whose lobe can reach h is
    // visited and weighed exactly. A degenerate footprint (zero area) or h below the surface gives 0.
    // With the box footprint and the isotropic cone (and no colour variation), boxes of facets that lie wholly
    // inside footprint and cone add their exact count without generating their facets (wholeBoxes = false
    // enumerates every facet: the tests check that both give the same count).
    FacetEstimate estimate(const PixelFootprint& fp, const glm::dvec3& h, bool wholeBoxes = true) const;

    // Calls visit(facet, weight) for every facet of the footprint (all normals): environment lighting.
    template <class Visit> void forEachFootprintFacet(const PixelFootprint& fp, Visit&& visit) const;

private:
    FacetRealization realization_;
    FootprintFilter filter_;
    double truncatedMass_ = 1.0;
    mutable std::once_flag ratioTableOnce_;
    mutable std::vector<double> ratioTable_;   // [azimuth][polar], lobeRatio
    static constexpr int kRatioPolar = 512, kRatioAzimuthAnisotropic = 64;
    template <class Integrand> double lobeIntegral(const glm::dvec3& h, Integrand&& integrand) const;
};

template <class Visit> void FacetEstimator::forEachFootprintFacet(const PixelFootprint& fp, Visit&& visit) const {
    FootprintTest footprint = footprintTest(fp);
    if (!footprint.valid) return;
    FacetRegion region;   // every normal
    region.uvMin = footprint.lo;
    region.uvMax = footprint.hi;
    realization_.forEach(region, [&](const Facet& f) {
        double w = footprint.weight(f.uv);
        if (w > 0.0) visit(f, w);
    });
}

}  // namespace glimmer::facets
