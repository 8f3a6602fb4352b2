#include "reference/discrete_facets/facet_estimator.h"

#include <algorithm>
#include <cmath>

namespace glimmer::facets {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kGaussianFootprintRadius = 3.5;   // Mahalanobis truncation of the Gaussian footprint
constexpr double kBoundaryTolerance = 1e-9;        // in footprint coordinates: the closed parallelogram

// 8-point Gauss-Legendre rule on [0, 1] (nodes and weights of [-1, 1] halved).
constexpr double kGlNodes[8] = {0.0198550717512319, 0.1016667612931866, 0.2372337950418355, 0.4082826787521751,
                                0.5917173212478249, 0.7627662049581645, 0.8983332387068134, 0.9801449282487681};
constexpr double kGlWeights[8] = {0.0506142681451881, 0.1111905172266872, 0.1568533229389436, 0.1813418916891810,
                                  0.1813418916891810, 0.1568533229389436, 0.1111905172266872, 0.0506142681451881};

// A unit tangent around h (the surface tangent x projected off h) and its bitangent: the axes of the anisotropic lobe.
void lobeAxes(const glm::dvec3& h, glm::dvec3& t, glm::dvec3& b) {
    t = glm::dvec3(1.0, 0.0, 0.0) - h * h.x;
    double len = glm::length(t);
    if (len < 1e-9) {
        t = glm::dvec3(0.0, 1.0, 0.0) - h * h.y;
        len = glm::length(t);
    }
    t /= len;
    b = glm::cross(h, t);
}
}  // namespace

FacetEstimator::FacetEstimator(const FacetMaterial& material, FootprintFilter filter)
    : realization_(material), filter_(filter) {
    if (filter_ == FootprintFilter::Gaussian)
        truncatedMass_ = 1.0 - std::exp(-0.5 * kGaussianFootprintRadius * kGaussianFootprintRadius);
}

double FacetEstimator::smoothD(const glm::dvec3& h) const {
    if (h.z <= 0.0) return 0.0;
    const double a2 = material().alpha * material().alpha, c2 = h.z * h.z;
    if (material().ndf == kNdfBeckmann) {
        double tan2 = (1.0 - c2) / c2;
        return std::exp(-tan2 / a2) / (kPi * a2 * c2 * c2);
    }
    double d = c2 * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

FacetEstimator::LobeTest FacetEstimator::lobeTest(const glm::dvec3& h) const {
    const FacetMaterial& mat = material();
    LobeTest test;
    test.h = h;
    lobeAxes(h, test.t, test.b);
    test.anisotropy = mat.anisotropy;
    test.cone = mat.lobe == Lobe::Cone;
    test.cosGamma = std::cos(mat.gamma);
    const double sigma = mat.gamma / std::sqrt(2.0);
    const double reach = test.cone ? std::sin(mat.gamma) : 4.0 * sigma;
    test.reach2 = reach * reach;
    test.inverseTwoSigma2 = 1.0 / (2.0 * sigma * sigma);
    return test;
}

template <class Integrand> double FacetEstimator::lobeIntegral(const glm::dvec3& h, Integrand&& integrand) const {
    const FacetMaterial& mat = material();
    const double a = mat.anisotropy;
    const double sigma = mat.gamma / std::sqrt(2.0);
    const bool cone = mat.lobe == Lobe::Cone;
    const double reach = cone ? std::sin(mat.gamma) : 4.0 * sigma;   // of e = sin(theta) x stretch (LobeTest)
    // Azimuth nodes: the lobe's extent varies as 1 / sqrt(cos^2 / a + a sin^2), sharper for larger a.
    const int azimuths = 32 * int(std::ceil(std::sqrt(a)));
    glm::dvec3 t, b;
    lobeAxes(h, t, b);
    double sum = 0.0;
    for (int j = 0; j < azimuths; ++j) {
        double psi = 2.0 * kPi * (double(j) + 0.5) / double(azimuths);
        double cp = std::cos(psi), sp = std::sin(psi);
        double stretch = std::sqrt(cp * cp / a + a * sp * sp);   // e = sin(theta) x stretch
        double thetaMax = std::asin(std::min(1.0, reach / stretch));
        glm::dvec3 axis = cp * t + sp * b;
        for (int k = 0; k < 8; ++k) {
            double theta = thetaMax * kGlNodes[k];
            double kernel = 1.0;
            if (!cone) {
                double e = std::sin(theta) * stretch;
                kernel = std::exp(-e * e / (2.0 * sigma * sigma));
            }
            glm::dvec3 m = std::cos(theta) * h + std::sin(theta) * axis;
            sum += kGlWeights[k] * thetaMax * std::sin(theta) * kernel * integrand(m);
        }
    }
    return sum * 2.0 * kPi / double(azimuths);
}

double FacetEstimator::lobeProbability(const glm::dvec3& h) const {
    return lobeIntegral(h, [this](const glm::dvec3& m) { return m.z > 0.0 ? smoothD(m) * m.z : 0.0; });
}

double FacetEstimator::lobeSolidAngle(const glm::dvec3& h) const {
    return lobeIntegral(h, [](const glm::dvec3&) { return 1.0; });
}

double FacetEstimator::lobeRatio(const glm::dvec3& h) const {
    const int azimuths = material().anisotropy == 1.0 ? 1 : kRatioAzimuthAnisotropic;
    // Polar nodes at theta_i = (pi / 2) i / (kRatioPolar - 1), azimuth nodes at 2 pi j / azimuths (periodic).
    std::call_once(ratioTableOnce_, [&] {
        ratioTable_.resize(size_t(azimuths) * kRatioPolar);
        for (int j = 0; j < azimuths; ++j)
            for (int i = 0; i < kRatioPolar; ++i) {
                double theta = std::min(0.5 * kPi * double(i) / double(kRatioPolar - 1), 0.5 * kPi - 1e-4);
                double phi = 2.0 * kPi * double(j) / double(azimuths);
                glm::dvec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
                double d = smoothD(n) * n.z;
                ratioTable_[size_t(j) * kRatioPolar + size_t(i)] = d > 0.0 ? lobeProbability(n) / d : 0.0;
            }
    });
    const double theta = std::acos(std::clamp(h.z, 0.0, 1.0));
    double x = theta / (0.5 * kPi) * double(kRatioPolar - 1);
    int i0 = std::clamp(int(x), 0, kRatioPolar - 2);
    double tx = std::clamp(x - double(i0), 0.0, 1.0);
    auto row = [&](int j) {
        const double* r = &ratioTable_[size_t(j) * kRatioPolar];
        return r[i0] + (r[i0 + 1] - r[i0]) * tx;
    };
    if (azimuths == 1) return row(0);
    double phi = std::atan2(h.y, h.x) / (2.0 * kPi);
    if (phi < 0.0) phi += 1.0;
    double y = phi * double(azimuths);
    int j0 = int(y) % azimuths;
    double ty = y - std::floor(y);
    return row(j0) + (row((j0 + 1) % azimuths) - row(j0)) * ty;
}

double FacetEstimator::footprintArea(const PixelFootprint& fp) {
    return std::abs(fp.duvdx.x * fp.duvdy.y - fp.duvdx.y * fp.duvdy.x);
}

FacetEstimator::FootprintTest FacetEstimator::footprintTest(const PixelFootprint& fp) const {
    FootprintTest test;
    test.centre = fp.uv;
    test.box = filter_ == FootprintFilter::Box;
    const double det = fp.duvdx.x * fp.duvdy.y - fp.duvdx.y * fp.duvdy.x;
    if (!(std::abs(det) > 1e-300) || !footprintBounds(fp, test.lo, test.hi)) return test;
    if (test.box) {
        // Footprint coordinates (s, t): uv = centre + s duv/dx + t duv/dy.
        test.m00 = fp.duvdy.y / det;
        test.m01 = -fp.duvdy.x / det;
        test.m10 = -fp.duvdx.y / det;
        test.m11 = fp.duvdx.x / det;
        test.edge = 0.5 + kBoundaryTolerance;
        test.scale = 1.0 / std::abs(det);
        test.valid = true;
        return test;
    }
    // Covariance J J^T / 12 (a unit square's second moments mapped by J).
    const double sxx = (fp.duvdx.x * fp.duvdx.x + fp.duvdy.x * fp.duvdy.x) / 12.0;
    const double syy = (fp.duvdx.y * fp.duvdx.y + fp.duvdy.y * fp.duvdy.y) / 12.0;
    const double sxy = (fp.duvdx.x * fp.duvdx.y + fp.duvdy.x * fp.duvdy.y) / 12.0;
    const double detS = sxx * syy - sxy * sxy;
    if (!(detS > 0.0)) return test;
    test.m00 = syy / detS;
    test.m01 = test.m10 = -sxy / detS;
    test.m11 = sxx / detS;
    test.reach2 = kGaussianFootprintRadius * kGaussianFootprintRadius * (1.0 + 2.0 * kBoundaryTolerance);
    test.scale = 1.0 / (2.0 * kPi * std::sqrt(detS) * truncatedMass_);
    test.valid = true;
    return test;
}

bool FacetEstimator::footprintBounds(const PixelFootprint& fp, glm::dvec2& lo, glm::dvec2& hi) const {
    if (!(footprintArea(fp) > 1e-300)) return false;
    glm::dvec2 half;
    if (filter_ == FootprintFilter::Box) {
        half = 0.5 * (glm::abs(fp.duvdx) + glm::abs(fp.duvdy));
    } else {
        const double sxx = (fp.duvdx.x * fp.duvdx.x + fp.duvdy.x * fp.duvdy.x) / 12.0;
        const double syy = (fp.duvdx.y * fp.duvdx.y + fp.duvdy.y * fp.duvdy.y) / 12.0;
        half = kGaussianFootprintRadius * glm::dvec2(std::sqrt(sxx), std::sqrt(syy));
    }
    // Widened a little, so that the exact test above (with its boundary tolerance) decides at the edges.
    half = half * (1.0 + 1e-6) + glm::dvec2(1e-9 * (std::abs(fp.uv.x) + std::abs(fp.uv.y)));
    lo = fp.uv - half;
    hi = fp.uv + half;
    return std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(hi.x) && std::isfinite(hi.y);
}

FacetEstimate FacetEstimator::estimate(const PixelFootprint& fp, const glm::dvec3& h, bool wholeBoxes) const {
    FacetEstimate result;
    if (h.z <= 0.0) return result;
    const double rho = material().densityPerUv;
    // P(h) from the tabulated P / (D (h.n)) (lobeRatio, within 1e-4 of the quadrature, built once per material):
    // the quadrature's 256 NDF evaluations per pixel and light were most of an image's cost at sparse densities.
    const double d = smoothD(h), p = lobeRatio(h) * d * h.z;
    if (!(rho > 0.0) || !(p > 0.0)) return result;
    const FootprintTest footprint = footprintTest(fp);
    if (!footprint.valid) return result;
    const LobeTest lobe = lobeTest(h);
    FacetRegion region = realization_.lobeRegion(h);
    region.uvMin = footprint.lo;
    region.uvMax = footprint.hi;
    glm::dvec3 sum(0.0);
    long tested = 0;
    auto visit = [&](const Facet& f) {
        ++tested;
        double w = footprint.weight(f.uv);
        if (w <= 0.0) return;
        double k = lobe.weight(f.m);
        if (k > 0.0) sum += (w * k) * f.color;
    };
    const FacetMaterial& mat = material();
    if (wholeBoxes && footprint.box && lobe.cone && mat.anisotropy == 1.0 && mat.colorVariation == 0.0) {
        // Every facet of a box that lies inside both the parallelogram and the cone has weight 1 / A, lobe 1 and
        // the material's colour: the box's exact facet count is added without generating them (dense pixels
        // hold thousands of reflecting facets). The parallelogram is convex, so its 4 UV corners decide; over a
        // box of normals narrower than pi in azimuth, the angle to h is largest at a corner (cos of the angle is
        // a sinusoid in the polar angle and in the azimuth, without an interior minimum there).
        auto inside = [&](const double* uvLo, const double* uvHi, const double* u1Lo, const double* u1Hi,
                          const double* u2Lo, const double* u2Hi) {
            if (*u2Hi - *u2Lo >= 0.5) return false;
            for (int c = 0; c < 4; ++c) {
                glm::dvec2 uv(c & 1 ? uvHi[0] : uvLo[0], c & 2 ? uvHi[1] : uvLo[1]);
                double dx = uv.x - footprint.centre.x, dy = uv.y - footprint.centre.y;
                double fs = footprint.m00 * dx + footprint.m01 * dy, ft = footprint.m10 * dx + footprint.m11 * dy;
                if (!(std::abs(fs) <= 0.5 && std::abs(ft) <= 0.5)) return false;
            }
            for (int c = 0; c < 4; ++c) {
                glm::dvec3 m = realization_.normalFromUniforms(c & 1 ? *u1Hi : *u1Lo, c & 2 ? *u2Hi : *u2Lo);
                if (!(glm::dot(m, h) >= lobe.cosGamma)) return false;
            }
            return true;
        };
        const glm::dvec3 whole = footprint.scale * mat.color;
        realization_.forEachOrCount(region, visit, inside, [&](uint32_t n) { sum += double(n) * whole; });
    } else {
        realization_.forEach(region, visit);
    }
    result.d = sum * (d / (rho * p));
    result.ratio = (result.d.x + result.d.y + result.d.z) / (3.0 * d);
    result.lambda = rho * footprintArea(fp) * p;
    result.facetsTested = tested;
    return result;
}

}  // namespace glimmer::facets
