// The exact discrete-facet reference (engine/reference/discrete_facets/, issue 36): its realization is a Poisson
// process of facets with normals from D(m) (m.n), and its estimate is normalized so that the mean is the smooth D.
// These tests check exactly those properties on controlled footprints (no GL): the mean of D_est over many
// disjoint footprints against D(h) within 2 % (both NDFs, three roughnesses, narrow and wide lobes, anisotropy,
// the Gaussian options); block sums of reflecting facets against the Poisson law (variance = mean, dark fraction
// e^-lambda) at three densities; determinism and independence from the query; a facet on a footprint's boundary
// counted by every footprint that holds it. Fixed seeds; tolerances in each test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>
#include <vector>

#include "reference/discrete_facets/environment_glints.h"
#include "reference/discrete_facets/extended_lights.h"
#include "reference/discrete_facets/facet_estimator.h"

using namespace glimmer;
using namespace glimmer::facets;

namespace {

constexpr double kPi = 3.14159265358979323846;

glm::dvec3 halfVector(double theta, double phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// Disjoint square footprints of side `side` on a grid of n x n, starting at `origin`.
PixelFootprint squarePixel(glm::dvec2 origin, double side, int x, int y) {
    PixelFootprint fp;
    fp.uv = origin + side * glm::dvec2(double(x) + 0.5, double(y) + 0.5);
    fp.duvdx = {side, 0.0};
    fp.duvdy = {0.0, side};
    return fp;
}

struct MeanCase {
    const char* name;
    int ndf;
    double alpha, gamma, anisotropy;
    Lobe lobe;
    FootprintFilter filter;
};

}  // namespace

// The quadrature of P(h) and of the lobe's solid angle (facet_estimator.h), which the normalization rests on: the
// cone's solid angle is 2 pi (1 - cos gamma) exactly, an anisotropic ellipse keeps about pi gamma^2, and for a
// narrow cone P(h) tends to pi gamma^2 D(h) (h.n) (the README's p).
TEST(DiscreteFacets, LobeQuadrature) {
    FacetMaterial m;
    m.alpha = 0.3;
    m.gamma = 0.015;
    FacetEstimator cone(m);
    glm::dvec3 h = halfVector(0.3, 0.7);
    EXPECT_NEAR(cone.lobeSolidAngle(h), 2.0 * kPi * (1.0 - std::cos(m.gamma)), 1e-10);
    double small = kPi * m.gamma * m.gamma * cone.smoothD(h) * h.z;
    EXPECT_NEAR(cone.lobeProbability(h) / small, 1.0, 2e-3);
    // The table estimate() reads: P / (D (h.n)) within 1e-4 of the quadrature, isotropic and anisotropic, from the
    // pole to grazing half vectors.
    for (double theta : {0.0, 0.1, 0.37, 0.8, 1.3})
        EXPECT_NEAR(cone.lobeRatio(halfVector(theta, 0.3)) * cone.smoothD(halfVector(theta, 0.3)) * halfVector(theta, 0.3).z /
                        cone.lobeProbability(halfVector(theta, 0.3)), 1.0, 1e-4) << theta;
    m.anisotropy = 9.0;
    FacetEstimator stretched(m);
    EXPECT_NEAR(stretched.lobeSolidAngle(h) / (kPi * m.gamma * m.gamma), 1.0, 1e-3);
    for (double phi : {0.0, 0.5, 2.9})
        EXPECT_NEAR(stretched.lobeRatio(halfVector(0.4, phi)) * stretched.smoothD(halfVector(0.4, phi)) *
                        halfVector(0.4, phi).z / stretched.lobeProbability(halfVector(0.4, phi)), 1.0, 1e-3) << phi;
    m.anisotropy = 1.0;
    m.lobe = Lobe::Gaussian;
    FacetEstimator gaussian(m);
    // 2 pi sigma^2 (1 - e^-8) with sigma = gamma / sqrt 2 (truncated at 4 sigma), small-angle.
    EXPECT_NEAR(gaussian.lobeSolidAngle(h) / (kPi * m.gamma * m.gamma * (1.0 - std::exp(-8.0))), 1.0, 1e-3);
}

// E[D_est] = D(h): the mean over 12 x 12 disjoint footprints with about 400 expected reflecting facets each (so
// the statistical error of the mean is about 0.4 % for the box and cone, less with the Gaussian options), at two
// half vectors per case (and at the pole, where the lobe holds every azimuth, for the first), within 2 %.
// Includes gamma = alpha / 2, where P(h) is 4 % away from the README's small-cone p (the exact normalization is
// what keeps the mean).
TEST(DiscreteFacets, MeanIsTheSmoothNdf) {
    const MeanCase cases[] = {
        {"GGX 0.3, gamma 0.015", kNdfGgx, 0.3, 0.015, 1.0, Lobe::Cone, FootprintFilter::Box},
        {"GGX 0.1, gamma 0.05", kNdfGgx, 0.1, 0.05, 1.0, Lobe::Cone, FootprintFilter::Box},
        {"Beckmann 0.6, gamma 0.005", kNdfBeckmann, 0.6, 0.005, 1.0, Lobe::Cone, FootprintFilter::Box},
        {"Beckmann 0.1, gamma 0.015, anisotropy 8", kNdfBeckmann, 0.1, 0.015, 8.0, Lobe::Cone, FootprintFilter::Box},
        {"GGX 0.3, Gaussian lobe and footprint", kNdfGgx, 0.3, 0.015, 1.0, Lobe::Gaussian, FootprintFilter::Gaussian},
        {"GGX 0.6, gamma 0.05, Gaussian lobe, anisotropy 4", kNdfGgx, 0.6, 0.05, 4.0, Lobe::Gaussian, FootprintFilter::Box},
    };
    const int n = 12;
    bool first = true;
    for (const MeanCase& c : cases) {
        std::vector<double> thetas = {0.6 * c.alpha, 1.5 * c.alpha};
        if (first) thetas.push_back(0.0);
        first = false;
        for (double theta : thetas) {
            FacetMaterial m;
            m.ndf = c.ndf;
            m.alpha = c.alpha;
            m.gamma = c.gamma;
            m.anisotropy = c.anisotropy;
            m.lobe = c.lobe;
            m.seed = 7;
            glm::dvec3 h = halfVector(std::min(theta, 1.2), 0.4);
            FacetEstimator probe(m, c.filter);
            // Density such that a footprint expects 400 reflecting facets.
            const double side = 1e-2;
            m.densityPerUv = 400.0 / (side * side * probe.lobeProbability(h));
            FacetEstimator estimator(m, c.filter);
            double sum = 0.0, lambda = 0.0;
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    FacetEstimate e = estimator.estimate(squarePixel({0.37, -1.3}, side, x, y), h);
                    sum += e.ratio;
                    lambda += e.lambda;
                }
            double mean = sum / double(n * n);
            EXPECT_NEAR(mean, 1.0, 0.02) << c.name << ", theta_h " << theta << " (lambda per pixel "
                                         << lambda / double(n * n) << ")";
        }
    }
}

// Over a box footprint the cone lobe counts facets: S x A is an integer, the number of reflecting facets, which must
// be Poisson with mean lambda = rho A P(h). At three densities (lambda per 4 x 4 block 0.4, 2.4 and 9.6), over 3600
// disjoint blocks of 4 x 4 disjoint pixels: block sums have variance / mean within 4 standard errors of 1 and a
// dark fraction (no reflecting facet) within 4 standard errors of e^-lambda; pixel counts are integers.
TEST(DiscreteFacets, BlockSumsArePoisson) {
    const glm::dvec3 h = halfVector(0.25, 1.1);
    for (double blockLambda : {0.4, 2.4, 9.6}) {
        FacetMaterial m;
        m.alpha = 0.3;
        m.gamma = 0.015;
        m.seed = 11;
        FacetEstimator probe(m);
        const double side = 1e-3;
        m.densityPerUv = blockLambda / 16.0 / (side * side * probe.lobeProbability(h));
        FacetEstimator estimator(m);
        const int blocks = 60, n = blocks * 4;
        std::vector<double> blockSum(size_t(blocks * blocks), 0.0);
        double maxFraction = 0.0;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                FacetEstimate e = estimator.estimate(squarePixel({-2.0, 5.0}, side, x, y), h);
                double count = e.ratio * e.lambda;
                maxFraction = std::max(maxFraction, std::abs(count - std::round(count)));
                blockSum[size_t((y / 4) * blocks + x / 4)] += std::round(count);
            }
        EXPECT_LT(maxFraction, 1e-6) << "counts are not integers";
        double mean = 0.0, var = 0.0, dark = 0.0;
        for (double s : blockSum) mean += s, dark += s == 0.0;
        mean /= double(blockSum.size());
        dark /= double(blockSum.size());
        for (double s : blockSum) var += (s - mean) * (s - mean);
        var /= double(blockSum.size() - 1);
        const double N = double(blockSum.size()), l = blockLambda;
        EXPECT_NEAR(mean, l, 4.0 * std::sqrt(l / N)) << "lambda " << l;
        // Standard error of a sample variance of Poisson(l) counts: sqrt((l + 2 l^2) / N).
        EXPECT_NEAR(var, l, 4.0 * std::sqrt((l + 2.0 * l * l) / N)) << "lambda " << l;
        double p0 = std::exp(-l);
        EXPECT_NEAR(dark, p0, 4.0 * std::sqrt(p0 * (1.0 - p0) / N) + 1e-3) << "lambda " << l;
    }
}

// The realization is a function of the material alone: the same facets for the same seed whether a region is
// asked for at once or in pieces (UV quarters, two ranges of the normal's polar uniform), two estimators give
// bit-identical estimates, and another seed gives another realization.
TEST(DiscreteFacets, RealizationIsDeterministicAndQueryIndependent) {
    FacetMaterial m;
    m.densityPerUv = 3e5;
    m.seed = 3;
    FacetRealization a(m), b(m);
    auto key = [](const Facet& f) { return std::make_tuple(f.uv.x, f.uv.y, f.m.x, f.m.y, f.m.z); };
    std::vector<std::tuple<double, double, double, double, double>> whole, pieces;
    FacetRegion region;
    region.uvMin = {0.1, 0.2};
    region.uvMax = {0.3, 0.35};
    a.forEach(region, [&](const Facet& f) { whole.push_back(key(f)); });
    const double midU = 0.17, midV = 0.31, midU1 = 0.42;
    for (int q = 0; q < 4; ++q)
        for (int r = 0; r < 2; ++r) {
            FacetRegion part = region;
            (q & 1 ? part.uvMin.x : part.uvMax.x) = midU;
            (q & 2 ? part.uvMin.y : part.uvMax.y) = midV;
            (r ? part.u1Min : part.u1Max) = midU1;
            b.forEach(part, [&](const Facet& f) { pieces.push_back(key(f)); });
        }
    std::sort(whole.begin(), whole.end());
    std::sort(pieces.begin(), pieces.end());
    // Facets exactly on a cut would be counted twice; none lies there (positions are not on dyadic values).
    EXPECT_EQ(whole, pieces);
    EXPECT_NEAR(double(whole.size()), m.densityPerUv * 0.2 * 0.15, 4.0 * std::sqrt(m.densityPerUv * 0.03));

    FacetEstimator e1(m), e2(m);
    int nonZero = 0;
    for (int i = 0; i < 50; ++i) {
        PixelFootprint fp = squarePixel({0.0, 0.0}, 0.03, i % 7, i / 7);
        glm::dvec3 h = halfVector(0.05 * i / 50.0, 0.3 * i);
        FacetEstimate x = e1.estimate(fp, h), y = e2.estimate(fp, h);
        EXPECT_EQ(x.d, y.d);
        nonZero += x.ratio > 0.0;
    }
    EXPECT_GT(nonZero, 10);   // the comparison saw facets
    // Counting whole boxes inside footprint and cone (dense footprints) gives the count of every facet enumerated.
    FacetMaterial dense = m;
    dense.densityPerUv = 1e11;
    FacetEstimator denseEstimator(dense);
    long fastTested = 0, allTested = 0;
    for (int i = 0; i < 6; ++i) {
        PixelFootprint fp = squarePixel({0.2, 0.1}, 0.004, i, 2 * i);
        glm::dvec3 h = halfVector(0.02 + 0.05 * i, 0.9 * i);
        FacetEstimate fast = denseEstimator.estimate(fp, h), all = denseEstimator.estimate(fp, h, false);
        EXPECT_GT(all.ratio * all.lambda, 500.0);
        EXPECT_EQ(std::round(fast.ratio * fast.lambda), std::round(all.ratio * all.lambda)) << "footprint " << i;
        fastTested += fast.facetsTested;
        allTested += all.facetsTested;
    }
    EXPECT_LT(fastTested, allTested);   // whole boxes were counted
    m.seed = 4;
    FacetRealization other(m);
    std::vector<std::tuple<double, double, double, double, double>> otherWhole;
    other.forEach(region, [&](const Facet& f) { otherWhole.push_back(key(f)); });
    std::sort(otherWhole.begin(), otherWhole.end());
    EXPECT_NE(otherWhole, whole);
}

// A facet on the edge between two footprints, or on the corner of four, is counted by each of them (closed
// parallelograms), for axis-aligned and sheared footprints: the reflecting facets of the pieces add up to those of
// the whole plus the shared facet once per extra footprint that holds it.
TEST(DiscreteFacets, BoundaryFacetCountedByEveryFootprintHoldingIt) {
    FacetMaterial m;
    m.densityPerUv = 1e6;
    m.seed = 5;
    FacetEstimator estimator(m);
    // A facet of the realization and the half vector it reflects exactly.
    FacetRegion region;
    region.uvMin = {0.5, 0.5};
    region.uvMax = {0.51, 0.51};
    std::vector<Facet> facets;
    estimator.realization().forEach(region, [&](const Facet& f) { facets.push_back(f); });
    ASSERT_FALSE(facets.empty());
    const Facet f = facets.front();
    auto count = [&](const PixelFootprint& fp) {
        FacetEstimate e = estimator.estimate(fp, f.m);
        return std::round(e.ratio * e.lambda);
    };
    const glm::dvec2 dx{2e-4, 0.5e-4}, dy{-0.3e-4, 1.7e-4};   // sheared parallelogram
    // Two footprints sharing the edge through f: f at s = +1/2 of the first, s = -1/2 of the second.
    PixelFootprint left{f.uv - 0.5 * dx, dx, dy}, right{f.uv + 0.5 * dx, dx, dy};
    PixelFootprint both{f.uv, 2.0 * dx, dy};   // their union
    double l = count(left), r = count(right), u = count(both);
    EXPECT_GE(l, 1.0);
    EXPECT_GE(r, 1.0);
    EXPECT_EQ(l + r, u + 1.0);
    // Four footprints sharing the corner at f.
    double corners = 0.0;
    for (int i = 0; i < 4; ++i) {
        glm::dvec2 c = f.uv + (i & 1 ? 0.5 : -0.5) * dx + (i & 2 ? 0.5 : -0.5) * dy;
        double n = count({c, dx, dy});
        EXPECT_GE(n, 1.0) << "corner footprint " << i;
        corners += n;
    }
    EXPECT_EQ(corners, count({f.uv, 2.0 * dx, 2.0 * dy}) + 3.0);
}

// The environment term (environment_glints.h) keeps the mean: under a constant sky, the facets' reflection of the
// map averaged over many disjoint footprints equals the smooth lobe's (the difference the reference adds averages
// to 0) within 2 % of the smooth value, at a density of about 30 facets per footprint. Under a sky that is bright
// in one half only, too. (Both estimates share the map lookup; the smooth one is stratified Monte Carlo.)
TEST(DiscreteFacets, EnvironmentGlintsKeepTheMean) {
    Material material;
    material.glinty = true;
    material.alpha = 0.3f;
    material.glint.density = 3e5f;
    material.glint.angularSize = 0.02f;
    SurfaceImage surface;
    surface.width = surface.height = 24;
    surface.cameraPosition = {0.0, 0.0, 1.0};
    surface.pixels.resize(24 * 24);
    const double side = 0.01;
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) {
            SurfacePixel& p = surface.pixels[size_t(y * 24 + x)];
            p.covered = true;
            p.material = 0;
            p.position = {0.3 + 0.001 * x, -0.2 + 0.001 * y, 0.0};   // the view stays near the normal
            p.normal = {0.0, 0.0, 1.0};
            p.tangent = {1.0, 0.0, 0.0};
            p.metallic = 1.0;
            p.baseColor = {0.9, 0.9, 0.9};
            p.footprint = squarePixel({0.0, 0.0}, side, x, y);
        }
    for (int sky = 0; sky < 2; ++sky) {
        envref::CubeImage cube;
        cube.size = 8;
        cube.rgba.assign(size_t(6) * 64 * 4, 1.0f);
        if (sky == 1)   // half the sky dark: +x faces and half of the y and z faces
            for (int face = 0; face < 6; ++face)
                for (int i = 0; i < 64; ++i) {
                    glm::vec3 d = envref::cubeTexelDirection(face, i % 8, i / 8, 8);
                    for (int c = 0; c < 3; ++c) cube.rgba[(size_t(face) * 64 + size_t(i)) * 4 + size_t(c)] = d.x > 0 ? 0.1f : 2.0f;
                }
        EnvironmentMap map(cube, 1.0, 0.0);
        ReferenceOptions options;
        options.progress = false;
        EnvironmentOptions many;
        many.smoothSamples = 4096;
        std::vector<glm::vec3> delta = environmentGlints(surface, {material}, map, options, many);
        // The smooth value alone: the same call with no facets reflecting (density 0 leaves L_ref = 0).
        Material none = material;
        none.glint.density = 0.0f;
        std::vector<glm::vec3> minusSmooth = environmentGlints(surface, {none}, map, options, many);
        double sumDelta = 0.0, sumSmooth = 0.0;
        for (size_t i = 0; i < delta.size(); ++i) sumDelta += delta[i].x, sumSmooth -= minusSmooth[i].x;
        ASSERT_GT(sumSmooth, 0.0);
        EXPECT_NEAR(sumDelta / sumSmooth, 0.0, 0.02) << "sky " << sky;
    }
}

// Issue 37: lights of a size in the reference (extended_lights.h). The shapes' ray tests; the smooth expectation M
// against its closed form for a small sphere; the glint factor N / M keeps mean 1 over many footprints, for a rect
// (each facet's lobe sampled) and for a small sphere (the light sampled, D_est counted at each direction), both NDFs;
// and a light much smaller than the facets' lobe gives the punctual count at its centre.
namespace {
struct LitPlane {
    FacetMaterial material;
    glm::dvec3 v = glm::normalize(glm::dvec3(0.3, 0.1, 1.0));
    static constexpr double kSide = 0.004;
    PixelFootprint pixel(int x, int y) const { return squarePixel({0.0, 0.0}, kSide, x, y); }
};
// The mirror direction of v about the normal tilted by `tilt` towards +x: where the light goes so that h sits off
// the normal (the NDF varies across the light).
glm::dvec3 mirrorOff(const glm::dvec3& v, double tilt) {
    glm::dvec3 h = glm::normalize(glm::dvec3(std::sin(tilt), 0.0, std::cos(tilt)));
    return glm::normalize(2.0 * glm::dot(v, h) * h - v);
}
}  // namespace

TEST(DiscreteFacets, LightShapesHitWhatTheyCover) {
    Light rect;
    rect.type = LightType::Rect;
    rect.vector = {0.0f, 0.0f, 2.0f};
    rect.spotDirection = {0.0f, 0.0f, -1.0f};   // faces the origin
    rect.right = {1.0f, 0.0f, 0.0f};
    rect.width = 2.0f;
    rect.height = 1.0f;
    LightShape r = lightShape(rect);
    const glm::dvec3 o(0.0);
    EXPECT_TRUE(r.hits(o, glm::normalize(glm::dvec3(0.9, 0.0, 2.0))));
    EXPECT_FALSE(r.hits(o, glm::normalize(glm::dvec3(1.1, 0.0, 2.0))));   // past the width's half (1)
    EXPECT_TRUE(r.hits(o, glm::normalize(glm::dvec3(0.0, 0.45, 2.0))));
    EXPECT_FALSE(r.hits(o, glm::normalize(glm::dvec3(0.0, 0.55, 2.0))));  // past the height's half (0.5)
    EXPECT_FALSE(r.hits(glm::dvec3(0.0, 0.0, 4.0), glm::dvec3(0.0, 0.0, -1.0)));   // behind a one-sided rect
    rect.twoSided = true;
    EXPECT_TRUE(lightShape(rect).hits(glm::dvec3(0.0, 0.0, 4.0), glm::dvec3(0.0, 0.0, -1.0)));
    Light disk = rect;
    disk.type = LightType::Disk;
    disk.twoSided = false;
    disk.radius = 0.5f;
    EXPECT_TRUE(lightShape(disk).hits(o, glm::normalize(glm::dvec3(0.35, 0.35, 2.0))));
    EXPECT_FALSE(lightShape(disk).hits(o, glm::normalize(glm::dvec3(0.4, 0.4, 2.0))));
    Light sphere;
    sphere.type = LightType::Sphere;
    sphere.vector = {0.0f, 0.0f, 2.0f};
    sphere.radius = 0.2f;
    const double edge = std::asin(0.1);   // sin of the silhouette's half-angle: 0.2 / 2
    EXPECT_TRUE(lightShape(sphere).hits(o, glm::dvec3(std::sin(edge - 1e-4), 0.0, std::cos(edge - 1e-4))));
    EXPECT_FALSE(lightShape(sphere).hits(o, glm::dvec3(std::sin(edge + 1e-4), 0.0, std::cos(edge + 1e-4))));
    Light sun;
    sun.vector = {0.0f, 0.0f, 1.0f};
    EXPECT_TRUE(lightShape(sun).hits(o, glm::dvec3(std::sin(0.0045), 0.0, std::cos(0.0045))));
    EXPECT_FALSE(lightShape(sun).hits(o, glm::dvec3(std::sin(0.0048), 0.0, std::cos(0.0048))));   // 0.53 deg / 2
    Light point;
    point.type = LightType::Point;
    EXPECT_EQ(lightShape(point).kind, LightShape::None);   // punctual: counted at its direction
    for (const LightShape& s : {r, lightShape(sphere)}) {
        glm::dvec3 axis;
        double halfAngle;
        s.boundingCone(o, axis, halfAngle);
        EXPECT_NEAR(axis.z, 1.0, 1e-12);
        EXPECT_GE(halfAngle, std::atan(std::sqrt(1.25) / 2.0) * (s.kind == LightShape::Rect ? 1.0 : 0.0));
    }
}

TEST(DiscreteFacets, ExtendedLightsKeepTheMeanAndTendToThePunctualCount) {
    const glm::dvec3 n(0.0, 0.0, 1.0), t(1.0, 0.0, 0.0), b(0.0, 1.0, 0.0), position(0.0);
    for (int ndf : {kNdfGgx, kNdfBeckmann}) {
        LitPlane plane;
        plane.material.alpha = 0.3;
        plane.material.gamma = 0.02;
        plane.material.ndf = ndf;
        plane.material.densityPerUv = 4e6;   // the tiny sphere below: about 0.1 facets per footprint reflect it
        plane.material.seed = 7;
        FacetEstimator estimator(plane.material);
        const glm::dvec3 towards = mirrorOff(plane.v, 0.25);

        // A rect 3 m away, 1.2 x 0.8 m, facing the point: wider than a facet's reflected lobe (its lobe is sampled).
        Light rect;
        rect.type = LightType::Rect;
        rect.vector = glm::vec3(3.0 * towards);
        rect.spotDirection = glm::vec3(-towards);
        rect.right = glm::vec3(glm::normalize(glm::cross(glm::dvec3(0.0, 1.0, 0.0), -towards)));
        rect.width = 1.2f;
        rect.height = 0.8f;
        // A sphere 5 m away of radius 0.02 m: 5e-5 sr, below a facet's reflected lobe (the light is sampled).
        Light sphere;
        sphere.type = LightType::Sphere;
        sphere.vector = glm::vec3(5.0 * towards);
        sphere.radius = 0.02f;
        const double sphereSolidAngle = 2.0 * kPi * (1.0 - std::sqrt(1.0 - 0.004 * 0.004));
        const glm::dvec3 hCentre = glm::normalize(towards + plane.v);

        for (const Light& light : {rect, sphere}) {
            // The sphere sees few facets per footprint: a denser material there keeps the test's error small.
            LitPlane lit = plane;
            lit.material.densityPerUv = light.type == LightType::Rect ? 2e7 : 2e8;
            FacetEstimator litEstimator(lit.material);
            const LightShape shape = lightShape(light);
            ExtendedLightOptions options;
            double sumFactor = 0.0, sumFactor2 = 0.0, sumExpected = 0.0;
            int pixels = 0;
            for (int y = 0; y < 20; ++y)
                for (int x = 0; x < 20; ++x) {
                    ExtendedEstimate e = estimateOverLight(litEstimator, lit.pixel(x, y), position, n, t, b, lit.v,
                                                           shape, options, uint64_t(y * 20 + x));
                    ASSERT_GT(e.expected, 0.0);
                    sumFactor += e.factor.x;
                    sumFactor2 += e.factor.x * e.factor.x;
                    sumExpected += e.expected;
                    ++pixels;
                }
            const char* which = light.type == LightType::Rect ? "rect" : "sphere";
            // The mean of N / M over 400 disjoint footprints within 4 standard errors (measured from the same
            // footprints) and 1 % of 1: a bias of a few percent fails.
            const double mean = sumFactor / pixels;
            const double standardError = std::sqrt(std::max(sumFactor2 / pixels - mean * mean, 0.0) / pixels);
            std::printf("%s ndf %d: mean factor %.4f, standard error %.4f\n", which, ndf, mean, standardError);
            EXPECT_LT(standardError, 0.03) << which;
            EXPECT_NEAR(mean, 1.0, 4.0 * standardError + 0.01) << which << " ndf " << ndf;
            if (light.type == LightType::Sphere)   // M = int D(h(l)) dl: D at the centre x the solid angle
                EXPECT_NEAR(sumExpected / pixels / (litEstimator.smoothD(hCentre) * sphereSolidAngle), 1.0, 0.02);
        }

        // A sphere far smaller than the facets' lobe: its factor is the punctual count at its centre, D_est / D.
        Light tiny = sphere;
        tiny.radius = 0.002f;
        double extended = 0.0, punctual = 0.0;
        for (int i = 0; i < 100; ++i) {
            const PixelFootprint fp = plane.pixel(i % 10, i / 10);
            extended += estimateOverLight(estimator, fp, position, n, t, b, plane.v, lightShape(tiny), {}, uint64_t(i))
                            .factor.x;
            punctual += estimator.estimate(fp, hCentre).ratio;
        }
        ASSERT_GT(punctual, 0.0);
        EXPECT_NEAR(extended / punctual, 1.0, 0.03) << "ndf " << ndf;
    }
}
