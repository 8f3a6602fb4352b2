// Issue 7, CPU side: the Kurt et al. 2010 BRDF and its sampling (Sec. 4), the regular patterns (Sec. 5), the
// per-sample MIP level (Sec. 6) and the constant pdf (Sec. 7) of "Real-time Rendering of Glossy Materials with
// Regular Sampling" (CGI 2014), against hand-computed counts and exact or quadrature references.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "core/error.h"
#include "environment/ibl/ibl_estimators.h"
#include "environment/ibl/kurt_brdf.h"
#include "environment/ibl/regular_pattern.h"

namespace glimmer::ibl {
namespace {

constexpr double kPi = std::numbers::pi;

glm::dvec3 viewAt(double thetaDeg, double phiDeg) {
    double t = thetaDeg * kPi / 180.0, p = phiDeg * kPi / 180.0;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// --- Sec. 5: Figure 4 ----------------------------------------------------------------------------------------

TEST(RegularSamplingPattern, Figure4CountsUnderTheDocumentedReading) {
    // Hand count, RingRule::Arc (nc = 3, xi0 = 0.1): s1 = pole + circles at s1 (n0 = 6) and 2 s1
    // (6 + 2 pi (sin 2s - sin s) / sin s = 6 + 2 pi (2 cos s - 1) ~ 12.28 -> 12) -> 19, as in Fig. 4.
    // s2 = circles at s2 (n0 = 4), 2 s2 (~10.28 -> 10), 3 s2 (~16.57 -> 16) -> 30, as in Fig. 4.
    for (double m : {0.05, 0.1, 0.3}) {
        RegularPattern s1 = generateRegularPattern({m, m, 0.1, 3, RingSpacing::S1});
        RegularPattern s2 = generateRegularPattern({m, m, 0.1, 3, RingSpacing::S2});
        EXPECT_EQ(s1.size(), 19) << "m=" << m;
        EXPECT_EQ(s1.ringCounts, (std::vector<int>{1, 6, 12})) << "m=" << m;
        EXPECT_EQ(s2.size(), 30) << "m=" << m;
        EXPECT_EQ(s2.ringCounts, (std::vector<int>{4, 10, 16})) << "m=" << m;
    }
    // The literal Eq. 13 (ratio of sines): 19 with s1, but 4 + 8 + 12 = 24 with s2.
    for (double m : {0.05, 0.1, 0.3, 0.6}) {
        RegularPattern s1 = generateRegularPattern({m, m, 0.1, 3, RingSpacing::S1, RingRule::Eq13});
        RegularPattern s2 = generateRegularPattern({m, m, 0.1, 3, RingSpacing::S2, RingRule::Eq13});
        EXPECT_EQ(s1.ringCounts, (std::vector<int>{1, 6, 12})) << "m=" << m;
        EXPECT_EQ(s2.ringCounts, (std::vector<int>{4, 8, 12})) << "m=" << m;
    }
    // Fig. 8: the isotropic material mx = my = 0.1 "approximated with 14 samples" (xi0 = 0.2): s2 with nc = 2,
    // 4 + 10, is reachable only under RingRule::Arc.
    EXPECT_EQ(selectPatternForBudget(0.1, 0.1, 0.2, 14).size(), 14);
    EXPECT_NE(selectPatternForBudget(0.1, 0.1, 0.2, 14, 24, RingRule::Eq13).size(), 14);
}

TEST(RegularSamplingPattern, RingGeometryFollowsEq11To13) {
    const double m = 0.2, xi0 = 0.1;
    double tmax = thetaMax(xi0, m, m);
    EXPECT_NEAR(std::tan(tmax), std::sqrt(std::log(10.0)) * m, 1e-12);   // Eq. 11
    // The xi0 border: q(theta_max) = xi0 exactly.
    glm::dvec3 border{std::sin(tmax), 0.0, std::cos(tmax)};
    EXPECT_NEAR(kurtQ(border, m, m), xi0, 1e-12);
    RegularPattern p = generateRegularPattern({m, m, xi0, 4, RingSpacing::S1});
    // Every ring sample lies at theta = k * theta_max / 5 (Eq. 12, s1).
    for (const glm::dvec3& h : p.halfVectors) {
        double k = std::acos(std::clamp(h.z, -1.0, 1.0)) / (tmax / 5.0);
        EXPECT_NEAR(k, std::round(k), 1e-9);
        EXPECT_NEAR(glm::length(h), 1.0, 1e-12);
    }
    // Eq. 13 rounds to the nearest even count, e.g. ratio 2.5 of sines -> 6 * 2.5 / 2 + 0.5 = 8 -> 16.
    EXPECT_EQ(ringSampleCount(6, std::asin(0.5), std::asin(0.2)), 16);
    EXPECT_EQ(ringSampleCount(4, std::asin(0.5), std::asin(0.2)), 10);
    EXPECT_EQ(ringSampleCount(6, 0.3, 0.3), 6);
    EXPECT_EQ(ringSampleCount(4, 0.3, 0.3), 4);
    // Arc rule: n0 + 2 pi (sin(theta_i) - sin(theta_0)) / sin(s): 4 + 2 pi * 0.3 / 0.2 = 13.42 -> 14.
    EXPECT_EQ(ringSampleCountArc(4, std::asin(0.5), std::asin(0.2), std::asin(0.2)), 14);
    EXPECT_EQ(ringSampleCountArc(6, 0.3, 0.3, 0.3), 6);
}

TEST(RegularSamplingPattern, AnisotropicPatternsAreSymmetricAndRejectBelowXi0) {
    for (auto spacing : {RingSpacing::S1, RingSpacing::S2}) {
        PatternParams params{0.2, 0.075, 0.1, 4, spacing};
        RegularPattern p = generateRegularPattern(params);
        RegularPattern iso = generateRegularPattern({0.2, 0.2, 0.1, 4, spacing});
        ASSERT_LT(p.size(), iso.size()) << "anisotropy must reject samples";
        for (const glm::dvec3& h : p.halfVectors) EXPECT_GE(kurtQ(h, 0.2, 0.075), 0.1);
        // Mirror symmetry about both tangent axes.
        auto contains = [&](glm::dvec3 v) {
            for (const glm::dvec3& h : p.halfVectors)
                if (glm::length(h - v) < 1e-9) return true;
            return false;
        };
        for (const glm::dvec3& h : p.halfVectors) {
            EXPECT_TRUE(contains({-h.x, h.y, h.z}));
            EXPECT_TRUE(contains({h.x, -h.y, h.z}));
        }
        // Each ring kept the better of the two half-offset variants and exactly its samples with q >= xi0.
        double tmax = p.thetaMax;
        int ringIndex = 0;
        bool s1 = spacing == RingSpacing::S1;
        double s = tmax / (params.nc + (s1 ? 1 : 2));
        for (int k = s1 ? 0 : 1; k <= (s1 ? params.nc - 1 : params.nc); ++k, ++ringIndex) {
            if (k == 0) { EXPECT_EQ(p.ringCounts[ringIndex], 1); continue; }
            int n = ringSampleCountArc(s1 ? 6 : 4, k * s, s, s);
            double best = -1.0;
            int bestCount = 0;
            for (double offset : {0.0, 0.5}) {
                double sum = 0.0;
                int count = 0;
                for (int j = 0; j < n; ++j) {
                    double phi = 2.0 * kPi * (j + offset) / n;
                    glm::dvec3 h{std::sin(k * s) * std::cos(phi), std::sin(k * s) * std::sin(phi), std::cos(k * s)};
                    double q = kurtQ(h, 0.2, 0.075);
                    if (q >= 0.1) { sum += q; ++count; }
                }
                if (sum > best * (1.0 + 1e-12)) { best = sum; bestCount = count; }
            }
            EXPECT_EQ(p.ringCounts[ringIndex], bestCount) << "ring " << k;
        }
    }
}

TEST(RegularSamplingPattern, IsotropicPatternsRejectNothing) {
    RegularPattern p = generateRegularPattern({0.15, 0.15, 0.01, 6, RingSpacing::S1});
    int expected = 1;
    double s = p.thetaMax / 7.0;
    for (int k = 1; k <= 5; ++k) expected += ringSampleCountArc(6, k * s, s, s);
    EXPECT_EQ(p.size(), expected);
}

TEST(RegularSamplingPattern, BudgetSelectionPicksTheClosestCount) {
    for (int budget : {5, 14, 17, 19, 30, 64, 270}) {
        RegularPattern chosen = selectPatternForBudget(0.2, 0.075, 0.1, budget);
        int bestDistance = 1 << 30;
        for (int nc = 1; nc <= 24; ++nc)
            for (auto sp : {RingSpacing::S1, RingSpacing::S2})
                bestDistance = std::min(bestDistance,
                                        std::abs(generateRegularPattern({0.2, 0.075, 0.1, nc, sp}).size() - budget));
        EXPECT_EQ(std::abs(chosen.size() - budget), bestDistance) << budget;
    }
    EXPECT_EQ(selectPatternForBudget(0.1, 0.1, 0.1, 19).size(), 19);
}

TEST(RegularSamplingPattern, BadParametersThrow) {
    EXPECT_THROW(generateRegularPattern({0.1, 0.1, 0.0, 3, RingSpacing::S1}), Error);
    EXPECT_THROW(generateRegularPattern({0.1, 0.1, 1.0, 3, RingSpacing::S1}), Error);
    EXPECT_THROW(generateRegularPattern({0.1, 0.1, 0.1, 0, RingSpacing::S1}), Error);
    EXPECT_THROW(generateRegularPattern({0.0, 0.1, 0.1, 3, RingSpacing::S1}), Error);
}

// --- Sec. 4: BRDF, sampling, pdf ------------------------------------------------------------------------------

TEST(RegularSamplingKurtBrdf, PdfEq10IntegratesToOneOverTheSphere) {
    for (auto [mx, my] : {std::pair{0.1, 0.1}, std::pair{0.2, 0.075}, std::pair{0.5, 0.3}}) {
        for (double viewTheta : {0.0, 40.0, 75.0}) {
            glm::dvec3 wo = viewAt(viewTheta, 30.0);
            // Quadrature over incident directions on the whole sphere (wi below the horizon included: Eq. 10 is a
            // density of reflected half-vector samples, not truncated). Grid in cos(theta), phi about wo's mirror.
            const int nt = 2000, np = 720;
            double sum = 0.0;
            for (int i = 0; i < nt; ++i) {
                double z = -1.0 + 2.0 * (i + 0.5) / nt;
                double r = std::sqrt(std::max(0.0, 1.0 - z * z));
                for (int j = 0; j < np; ++j) {
                    double phi = 2.0 * kPi * (j + 0.5) / np;
                    glm::dvec3 wi{r * std::cos(phi), r * std::sin(phi), z};
                    sum += kurtPdf(wi, wo, mx, my);
                }
            }
            sum *= (2.0 / nt) * (2.0 * kPi / np);
            // Exact total: the half-vector mass with wo.h > 0 (half vectors facing away from wo reflect nothing),
            // integrated over half-vector directions instead (a different grid, no Jacobian): checks Eq. 10's
            // 1 / (4 wo.h) change of variables.
            double reachable = 0.0;
            const int ht = 1500, hp = 720;
            for (int i = 0; i < ht; ++i) {
                double theta = (i + 0.5) / ht * 0.5 * kPi;
                for (int j = 0; j < hp; ++j) {
                    double phi = 2.0 * kPi * (j + 0.5) / hp;
                    glm::dvec3 h{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
                    if (glm::dot(h, wo) <= 0.0) continue;
                    reachable += kurtHalfVectorPdf(h, mx, my) * std::sin(theta);
                }
            }
            reachable *= (0.5 * kPi / ht) * (2.0 * kPi / hp);
            EXPECT_NEAR(sum, reachable, 0.01) << mx << "," << my << " view " << viewTheta;
            if (viewTheta < 50.0) EXPECT_NEAR(sum, 1.0, 0.01) << mx << "," << my << " view " << viewTheta;
        }
    }
}

TEST(RegularSamplingKurtBrdf, SamplingEq6To7FollowsThePdf) {
    // Moments of the sampled half vectors against quadrature of the half-vector pdf (q / (pi mx my cos^3)).
    const double mx = 0.3, my = 0.1;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 200000;
    double mx2 = 0.0, my2 = 0.0, mz = 0.0, quadrant = 0.0;
    for (int i = 0; i < n; ++i) {
        glm::dvec3 h = sampleKurtHalfVector(1.0 - u(rng), u(rng), mx, my);
        mx2 += h.x * h.x; my2 += h.y * h.y; mz += h.z;
        quadrant += (h.x > 0 && h.y > 0) ? 1.0 : 0.0;
    }
    mx2 /= n; my2 /= n; mz /= n; quadrant /= n;
    double qx2 = 0, qy2 = 0, qz = 0, mass = 0;
    const int nt = 1500, np = 720;
    for (int i = 0; i < nt; ++i) {
        double theta = (i + 0.5) / nt * 0.5 * kPi;
        for (int j = 0; j < np; ++j) {
            double phi = 2.0 * kPi * (j + 0.5) / np;
            glm::dvec3 h{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
            double w = kurtHalfVectorPdf(h, mx, my) * std::sin(theta) * (0.5 * kPi / nt) * (2.0 * kPi / np);
            mass += w; qx2 += w * h.x * h.x; qy2 += w * h.y * h.y; qz += w * h.z;
        }
    }
    EXPECT_NEAR(mass, 1.0, 1e-3);
    EXPECT_NEAR(mx2, qx2, 0.01 * qx2 + 3e-4);
    EXPECT_NEAR(my2, qy2, 0.02 * qy2 + 1e-4);
    EXPECT_NEAR(mz, qz, 1e-3);
    EXPECT_NEAR(quadrant, 0.25, 0.004);   // atan2 keeps all four quadrants
}

TEST(RegularSamplingKurtBrdf, LobeMatchesEq2To5ByHand) {
    KurtLobe lobe{1.0, 0.04, 0.2, 0.1, 0.5};
    glm::dvec3 wo = viewAt(30.0, 0.0), wi = viewAt(50.0, 200.0);
    glm::dvec3 h = glm::normalize(wi + wo);
    double theta = std::acos(h.z), phi = std::atan2(h.y, h.x);
    double q = std::exp(-std::tan(theta) * std::tan(theta) *
                        (std::cos(phi) * std::cos(phi) / 0.04 + std::sin(phi) * std::sin(phi) / 0.01));
    double d = q / (kPi * 0.2 * 0.1 * std::pow(std::cos(theta), 4.0));
    double u = glm::dot(wo, h);
    double f = 0.04 + 0.96 * std::pow(1.0 - u, 5.0);
    double expected = f * d / (4.0 * u * std::pow(wi.z * wo.z, 0.5));
    EXPECT_NEAR(kurtLobe(wi, wo, lobe), expected, 1e-12 * expected);
    KurtMaterial material{0.3, {lobe, KurtLobe{0.5, 1.0, 0.05, 0.05, 0.0}}};
    double two = 0.3 / kPi + expected + 0.5 * kurtLobe(wi, wo, material.lobes[1]);
    EXPECT_NEAR(kurtBrdf(wi, wo, material), two, 1e-12);
    EXPECT_EQ(kurtBrdf(glm::dvec3(0, 0, -1), wo, material), 0.0);
}

// --- Sec. 6-7: MIP level and estimators ---------------------------------------------------------------------

TEST(RegularSamplingMip, EllipseAreaAndDistortionTerms) {
    // Normal view: the extreme half vectors at angle a reflect to 2a from the mirror direction, so u = tan(2a).
    const double mx = 0.2, my = 0.1, xi0 = 0.1;
    double aU = std::atan(std::sqrt(std::log(10.0)) * mx), aV = std::atan(std::sqrt(std::log(10.0)) * my);
    EXPECT_NEAR(lobeCrossSectionArea({0, 0, 1}, mx, my, xi0), kPi * std::tan(2 * aU) * std::tan(2 * aV), 1e-9);
    // Eq. 16: face-centre direction, h = wi: A N / (4 n).
    EXPECT_NEAR(pixelsPerSample(0.4, 256 * 256, 16, {0, 0, 1}, 1.0), 0.4 * 65536 / 64.0, 1e-9);
    // A cube corner is sqrt(3) away; half-vector term 1 / (wi.h).
    glm::dvec3 corner = glm::normalize(glm::dvec3(1, 1, 1));
    EXPECT_NEAR(pixelsPerSample(0.4, 65536, 16, corner, 0.5), 0.4 * 65536 / 64.0 * std::sqrt(3.0) * 2.0, 1e-6);
    EXPECT_NEAR(mipLevelForSample(1024.0, 0.0), 5.0, 1e-12);   // log4
    EXPECT_NEAR(mipLevelForSample(1024.0, -1.0), 4.0, 1e-12);
    EXPECT_EQ(mipLevelForSample(0.5, 0.0), 0.0);
}

// Smooth analytic environment: the estimators are then compared with the quadrature of Eq. 8 at level 0.
glm::dvec3 smoothSky(glm::dvec3 d, double) {
    return {1.0 + 0.5 * d.x, 1.0 + 0.5 * d.y * d.y, 0.5 + std::max(d.z, 0.0)};
}

TEST(RegularSamplingEstimators, RegularConvergesToTheIntegralWithDensePatterns) {
    for (auto [mx, my] : {std::pair{0.1, 0.1}, std::pair{0.2, 0.075}}) {
        KurtLobe lobe{1.0, 1.0, mx, my, 0.0};
        for (double viewTheta : {0.0, 35.0}) {
            glm::dvec3 wo = viewAt(viewTheta, 20.0);
            glm::dvec3 ref = quadratureLobe(wo, lobe, smoothSky, 800, 400);
            RegularPattern coarse = generateRegularPattern({mx, my, 0.1, 3, RingSpacing::S1});
            RegularPattern dense = generateRegularPattern({mx, my, 0.001, 24, RingSpacing::S1});
            glm::dvec3 a = regularLobe(wo, lobe, coarse, smoothSky, 256, 0.0);
            glm::dvec3 b = regularLobe(wo, lobe, dense, smoothSky, 256, 0.0);
            double errCoarse = glm::length(a - ref) / glm::length(ref);
            double errDense = glm::length(b - ref) / glm::length(ref);
            EXPECT_LT(errDense, 0.02) << mx << "," << my << " view " << viewTheta;
            EXPECT_LT(errDense, errCoarse + 1e-3);
        }
    }
}

TEST(RegularSamplingEstimators, FisConvergesToTheIntegral) {
    KurtLobe lobe{1.0, 1.0, 0.2, 0.075, 0.0};
    glm::dvec3 wo = viewAt(35.0, 20.0);
    glm::dvec3 ref = quadratureLobe(wo, lobe, smoothSky, 800, 400);
    // Level-0 lookups (the analytic sky ignores lod): a pure importance-sampling estimate.
    glm::dvec3 est = fisLobe(wo, lobe, 4096, {0.3, 0.7}, smoothSky, 256, 0.0);
    EXPECT_LT(glm::length(est - ref) / glm::length(ref), 0.01);
}

}  // namespace
}  // namespace glimmer::ibl
