// The area lights' linearly transformed cosines on the CPU (engine/reference/area_light_reference.h, the mirror of
// shaders/lights/ltc.glsl; tables fitted at build time by tools/ltc_fit), against brute-force quadrature:
// - the closed forms: the clamped cosine over a sphere cap cut by the horizon (exact), over polygons (clipped,
//   exact) and over the cones of disks (exact above the horizon, the cap approximation across it);
// - the tables: the lobes' magnitudes (split-sum A and B, the NDF-only integral) and the total NDF of Kneiphof &
//   Klein 2024 (closed forms and their fit);
// - the LTC specular (GGX, Beckmann) and NDF-only integrals over rect, disk and sphere lights: error relative to the
//   lobe's magnitude (what a render shows), with the table of errors printed for docs/area_lights.md.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ltc_fitter.h"
#include "reference/area_light_reference.h"
#include "render/lights/ltc_tables.h"

namespace glimmer {
namespace {

using reference::AreaLightGeometry;
using reference::AreaShape;
namespace lf = ltcfit;

constexpr double kPi = 3.14159265358979323846;

// A light whose front faces the origin.
AreaLightGeometry rect(glm::dvec3 centre, glm::dvec3 u, glm::dvec3 v) {
    AreaLightGeometry g;
    g.shape = AreaShape::Rect;
    g.centre = centre;
    g.halfU = u;
    g.halfV = v;
    if (glm::dot(-centre, glm::cross(u, v)) < 0.0) g.halfU = -u;
    return g;
}
AreaLightGeometry disk(glm::dvec3 centre, glm::dvec3 normal, double radius) {
    AreaLightGeometry g;
    g.shape = AreaShape::Disk;
    g.centre = centre;
    normal = glm::normalize(normal);
    glm::dvec3 t = glm::normalize(glm::cross(normal, std::abs(normal.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    g.halfU = radius * t;
    g.halfV = radius * glm::cross(normal, t);   // cross(U, V) = normal
    g.radius = radius;
    if (glm::dot(-centre, normal) < 0.0) g.halfU = -g.halfU;
    return g;
}
AreaLightGeometry sphere(glm::dvec3 centre, double radius) {
    AreaLightGeometry g;
    g.shape = AreaShape::Sphere;
    g.centre = centre;
    g.radius = radius;
    return g;
}

double cosineLobe(const glm::dvec3& l) { return std::max(l.z, 0.0) / kPi; }

TEST(AreaLightLtc, CapCosineMatchesQuadratureAcrossTheHorizon) {
    // Spheres of half-angle 5..60 degrees from the zenith to below the horizon.
    double worst = 0.0;
    for (double sigma : {0.09, 0.4, 1.0})
        for (double elevation : {1.4, 0.9, 0.3, 0.05, -0.2, -0.6}) {
            double d = 2.0;
            glm::dvec3 c(d * std::cos(elevation), 0.3 * d * std::cos(elevation), d * std::sin(elevation));
            c = d * glm::normalize(c);
            AreaLightGeometry s = sphere(c, d * std::sin(sigma));
            double reference = reference::integrateOverLight(s, glm::dvec3(0.0), cosineLobe, 400);
            double closed = reference::capCosineIntegral(std::sin(sigma) * std::sin(sigma), c.z / d);
            worst = std::max(worst, std::abs(closed - reference));
            EXPECT_NEAR(closed, reference, 2e-4 + 2e-3 * reference) << "sigma " << sigma << " elevation " << elevation;
        }
    std::printf("cap form factor: worst |error| %.2e\n", worst);
}

TEST(AreaLightLtc, DiffuseFormFactorsMatchQuadrature) {
    const glm::dmat3 identity(1.0);
    const glm::dmat3 frame = reference::ltcFrame({0, 0, 1}, glm::normalize(glm::dvec3(0.3, 0.1, 1.0)));
    struct Case {
        const char* name;
        AreaLightGeometry light;
        double tolerance;   // relative: exact closed forms, or the cap approximation of a disk cut by the horizon
    };
    const Case cases[] = {
        {"rect above", rect({0.5, 0.3, 1.5}, {0.6, 0, 0}, {0, 0.3, 0.1}), 2e-3},
        {"rect across the horizon", rect({1.0, 0.2, 0.1}, {0, 0.8, 0}, {0.2, 0, 0.5}), 2e-3},
        {"disk above", disk({-0.4, 0.2, 1.2}, {0.2, -0.1, -1.0}, 0.5), 2e-3},
        {"disk tilted", disk({0.8, 0.0, 0.9}, {-1.0, 0.0, -0.2}, 0.4), 2e-3},
        {"disk across the horizon", disk({1.2, 0.0, 0.15}, {-1.0, 0.1, 0.0}, 0.4), 0.08},
        {"sphere", sphere({0.8, 0.1, 1.0}, 0.3), 2e-3},
        {"sphere across the horizon", sphere({1.5, 0.1, 0.1}, 0.3), 2e-3},
    };
    for (const Case& c : cases) {
        double reference = reference::integrateOverLight(c.light, glm::dvec3(0.0), [&](const glm::dvec3& l) {
            return cosineLobe(frame * l);
        }, 400);
        double closed = reference::ltcIntegral(c.light, glm::dvec3(0.0), frame, identity);
        std::printf("form factor %-26s %.5f (quadrature %.5f, %+.2f%%)\n", c.name, closed, reference,
                    100.0 * (closed / reference - 1.0));
        EXPECT_NEAR(closed, reference, c.tolerance * reference + 1e-5) << c.name;
    }
    // A one-sided light seen from behind sends nothing.
    AreaLightGeometry back = rect({0.0, 0.0, 1.0}, {0.5, 0, 0}, {0, 0.5, 0});
    back.halfU = -back.halfU;
    EXPECT_EQ(reference::ltcIntegral(back, glm::dvec3(0.0), frame, identity), 0.0);
}

TEST(AreaLightLtc, TotalNdfClosedFormsAndFitMatchQuadrature) {
    double worstFit = 0.0;
    for (double alpha : {0.02, 0.1, 0.3, 0.6, 1.0})
        for (int ndf = 0; ndf < 2; ++ndf) {
            // Integral of D over the hemisphere by the midpoint rule in theta (D is smooth in theta).
            const int n = 200000;
            double sum = 0.0;
            for (int i = 0; i < n; ++i) {
                double theta = (i + 0.5) / n * 0.5 * kPi;
                glm::dvec3 h(std::sin(theta), 0.0, std::cos(theta));
                sum += lf::ndfValue(lf::Ndf(ndf), h, alpha) * 2.0 * kPi * std::sin(theta) * (0.5 * kPi / n);
            }
            EXPECT_NEAR(lf::totalNdf(lf::Ndf(ndf), alpha), sum, 2e-4 * sum) << "alpha " << alpha << " ndf " << ndf;
            if (ndf == 0) worstFit = std::max(worstFit, std::abs(1.0 + std::pow(alpha, 1.4109) - sum) / sum);
        }
    std::printf("total NDF: GGX fit 1 + alpha^1.4109 within %.2f%% of the integral\n", 100.0 * worstFit);
    EXPECT_LT(worstFit, 0.03);
}

// The tables' magnitudes against an independent quadrature (uniform directions over the hemisphere, not the fitter's
// importance sampling): A, B of the specular lobe and the NDF-only integral, at the table's own entries.
TEST(AreaLightLtc, TableMagnitudesMatchHemisphereQuadrature) {
    const int n = ltc::kTableSize;
    for (int ndf = 0; ndf < 2; ++ndf)
        for (int row : {n / 4, n / 2, n - 1})
            for (int column : {0, n / 3, 2 * n / 3}) {
                double alpha = lf::rowAlpha(row, n), cosTheta = lf::columnCosTheta(column, n);
                glm::dvec3 v(std::sqrt(1.0 - cosTheta * cosTheta), 0.0, cosTheta);
                const int m = 600;
                double a = 0.0, b = 0.0, d = 0.0;
                for (int i = 0; i < m; ++i)
                    for (int j = 0; j < m; ++j) {
                        double z = (i + 0.5) / m, phi = 2.0 * kPi * (j + 0.5) / m, r = std::sqrt(1.0 - z * z);
                        glm::dvec3 l(r * std::cos(phi), r * std::sin(phi), z);
                        double w = 2.0 * kPi / (double(m) * m);
                        glm::dvec3 h = glm::normalize(v + l);
                        double fc = std::pow(1.0 - glm::dot(v, h), 5.0);
                        double spec = lf::lobeValue(lf::Ndf(ndf), lf::Lobe::Specular, alpha, v, l) * w;
                        a += spec * (1.0 - fc);
                        b += spec * fc;
                        d += lf::lobeValue(lf::Ndf(ndf), lf::Lobe::NdfOnly, alpha, v, l) * w;
                    }
                const float* e = ltc::tableEntry(ltc::kMagnitudeLayer + ndf, row, column);
                EXPECT_NEAR(e[0], a, 0.01 * a + 1e-3) << "A ndf " << ndf << " alpha " << alpha << " cos " << cosTheta;
                EXPECT_NEAR(e[1], b, 0.02 * b + 1e-3) << "B ndf " << ndf << " alpha " << alpha << " cos " << cosTheta;
                EXPECT_NEAR(e[2], d, 0.01 * d + 1e-3) << "NDF-only ndf " << ndf << " alpha " << alpha << " cos " << cosTheta;
            }
}

// The LTC integrals of the specular lobe and of the NDF-only lobe over each light shape against brute-force
// quadrature of the lobes, over roughnesses and view angles: |LTC - quadrature| / the lobe's magnitude. The
// bounds are this table's worst cases with a margin; Beckmann lobes (narrow core, light tails) are farther from a
// clamped cosine than GGX (which is one, stretched) and fit worse.
TEST(AreaLightLtc, LtcIntegralsMatchBruteForcePerShape) {
    const glm::dvec3 n(0.0, 0.0, 1.0);
    struct Shape {
        const char* name;
        AreaLightGeometry light;
    };
    const Shape shapes[] = {
        {"rect", rect({-0.6, 0.1, 1.0}, {0.3, 0, 0}, {0, 0.4, 0.05})},
        {"rect (large)", rect({-0.5, 0.2, 1.2}, {1.2, 0, 0}, {0, 0.8, 0.1})},
        {"disk", disk({-0.5, 0.1, 1.1}, {0.3, -0.1, -1.0}, 0.35)},
        {"sphere", sphere({-0.5, 0.0, 1.2}, 0.2)},
    };
    double worst[2][2] = {{0, 0}, {0, 0}};   // [ndf][specular, NDF-only]
    for (const Shape& shape : shapes)
        for (int ndf = 0; ndf < 2; ++ndf) {
            double sum[2] = {0, 0}, max[2] = {0, 0};
            int cases = 0;
            for (double alpha : {0.1, 0.3, 0.6})
                for (double theta : {0.2, 0.5, 0.9}) {
                    glm::dvec3 v(std::sin(theta), 0.0, std::cos(theta));
                    glm::dmat3 frame = reference::ltcFrame(n, v);
                    reference::LtcLookup look = reference::ltcLookup(alpha, v.z, ndf == 1);
                    double magnitude[2] = {look.A + look.B, look.ndfOnlyIntegral};
                    double ltcValue[2] = {magnitude[0] * reference::ltcIntegral(shape.light, glm::dvec3(0.0), frame, look.invSpecular),
                                          magnitude[1] * reference::ltcIntegral(shape.light, glm::dvec3(0.0), frame, look.invNdfOnly)};
                    for (int lobe = 0; lobe < 2; ++lobe) {
                        double quadrature = reference::integrateOverLight(shape.light, glm::dvec3(0.0), [&](const glm::dvec3& l) {
                            return lf::lobeValue(lf::Ndf(ndf), lf::Lobe(lobe), alpha, v, l);
                        }, 200);
                        double error = std::abs(ltcValue[lobe] - quadrature) / magnitude[lobe];
                        sum[lobe] += error;
                        max[lobe] = std::max(max[lobe], error);
                    }
                    ++cases;
                }
            for (int lobe = 0; lobe < 2; ++lobe) worst[ndf][lobe] = std::max(worst[ndf][lobe], max[lobe]);
            std::printf("LTC %-12s %-8s specular mean %.3f max %.3f   NDF-only mean %.3f max %.3f  (of the lobe)\n",
                        shape.name, ndf == 0 ? "GGX" : "Beckmann", sum[0] / cases, max[0], sum[1] / cases, max[1]);
        }
    EXPECT_LT(worst[0][0], 0.05) << "GGX specular";
    EXPECT_LT(worst[0][1], 0.08) << "GGX NDF-only";
    EXPECT_LT(worst[1][0], 0.15) << "Beckmann specular";
    EXPECT_LT(worst[1][1], 0.15) << "Beckmann NDF-only";
}

// The fit is deterministic (a small table fitted twice is bit-identical: the build regenerates the same tables
// from the same fitter), and the shipped tables are normalized LTCs: over the upper hemisphere of light directions
// the specular LTC integrates to at most 1, and close to 1 where the lobe stays above the horizon.
TEST(AreaLightLtc, FitIsDeterministicAndTheTablesAreNormalized) {
    lf::FitSettings settings;
    settings.size = 4;
    std::vector<lf::Entry> a = lf::fitTable(lf::Ndf::Ggx, lf::Lobe::Specular, settings);
    std::vector<lf::Entry> b = lf::fitTable(lf::Ndf::Ggx, lf::Lobe::Specular, settings);
    for (size_t i = 0; i < a.size(); ++i)
        for (int k = 0; k < 4; ++k) EXPECT_EQ(a[i].invM[size_t(k)], b[i].invM[size_t(k)]);
    // The upper hemisphere as a "light": a large sphere cap of half-angle 89.9 degrees at the zenith.
    const glm::dvec3 n(0.0, 0.0, 1.0);
    AreaLightGeometry sky = sphere({0.0, 0.0, 1000.0}, 999.99);
    for (double alpha : {0.2, 0.5, 1.0})
        for (double theta : {0.0, 0.6}) {
            glm::dvec3 v(std::sin(theta), 0.0, std::cos(theta));
            reference::LtcLookup look = reference::ltcLookup(alpha, v.z, false);
            double total = reference::ltcIntegral(sky, glm::dvec3(0.0), reference::ltcFrame(n, v), look.invSpecular);
            EXPECT_LE(total, 1.001);
            EXPECT_GT(total, 0.9) << "alpha " << alpha << " theta " << theta;
        }
}

}  // namespace
}  // namespace glimmer
