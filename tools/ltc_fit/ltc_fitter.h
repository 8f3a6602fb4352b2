// Fitting of linearly transformed cosines (Heitz, Dupuy, Hill, Neubelt 2016, "Real-Time Polygonal-Light Shading
// with Linearly Transformed Cosines", ACM TOG 35(4), Sec. 4 and 5): for each roughness alpha and view angle theta,
// the 3 x 3 matrix M whose transformed clamped cosine D(l) = D_o(M^-1 l / |M^-1 l|) |M^-1| / |M^-1 l|^3
// (Eq. 1-3) is closest to a lobe of the BRDF, plus the lobe's magnitude and Fresnel term (Sec. 4.3). Used by the
// build-time generator (tools/ltc_fit/ltc_fit_main.cpp, which writes the engine's tables) and by the tests that
// re-fit entries and check the tables. Everything is deterministic: fixed stratified quadratures, no threads.
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <vector>

namespace glimmer::ltcfit {

enum class Ndf { Ggx = 0, Beckmann = 1 };

// The lobe a table approximates, as a function of the light direction l for a view v (shading frame, z = normal):
// - Specular: the project's Cook-Torrance BRDF times the cosine, D G1(l) G1(v) / (4 v.z) (Fresnel 1; separable
//   Smith, shaders/common/brdf.glsl), restricted to l.z > 0.
// - NdfOnly: the NDF carried to light directions, D(h) / (4 |v.h|) with h = normalize(v + l), l.z > 0 (Kneiphof &
//   Klein 2024, Sec. 4: the integrand of the probability that a facet reflects a light towards v).
enum class Lobe { Specular = 0, NdfOnly = 1 };

double ndfValue(Ndf ndf, const glm::dvec3& h, double alpha);
double lobeValue(Ndf ndf, Lobe lobe, double alpha, const glm::dvec3& v, const glm::dvec3& l);
// Integral of D over the hemisphere of half vectors (not projected): 1 + alpha^2 ln((1 + sqrt(1 - alpha^2)) /
// alpha) / sqrt(1 - alpha^2) for GGX, 1 + sqrt(pi) alpha e^(1/alpha^2) erfc(1/alpha) / 2 for Beckmann.
double totalNdf(Ndf ndf, double alpha);

// Integrals of a lobe over the light directions of the upper hemisphere, by a stratified quadrature with half
// vectors drawn from D(h) (h.n) (samplesPerAxis^2 points).
struct LobeIntegrals {
    double magnitude = 0.0;   // Specular: A + B; NdfOnly: the integral of D(h) / (4 |v.h|)
    double fresnel = 0.0;     // Specular: B = integral x (1 - v.h)^5 (Schlick's part; the split sum's "B")
    glm::dvec3 average{0.0, 0.0, 1.0};   // normalized first moment (its y is 0 by symmetry)
};
LobeIntegrals integrateLobe(Ndf ndf, Lobe lobe, double alpha, double cosTheta, int samplesPerAxis);

// A linearly transformed cosine M = [X Y Z] [[m11, 0, m13], [0, m22, 0], [0, 0, 1]] (Heitz et al.'s isotropic
// parameterization: a frame from the lobe's average direction, two scales and a skew).
struct Ltc {
    glm::dvec3 X{1.0, 0.0, 0.0}, Y{0.0, 1.0, 0.0}, Z{0.0, 0.0, 1.0};
    double m11 = 1.0, m22 = 1.0, m13 = 0.0;
    glm::dmat3 M{1.0}, invM{1.0};
    double detInvM = 1.0;
    void update();
    double eval(const glm::dvec3& l) const;                 // density over the sphere
    glm::dvec3 sample(double u1, double u2) const;          // cosine sample mapped by M
};

// One table entry: M^-1 divided by its (1, 1) entry, so that it is [[a, 0, b], [0, 1, 0], [c, 0, d]] (a direction
// function is unchanged by a uniform scale of M^-1), and the lobe's integrals.
struct Entry {
    std::array<float, 4> invM{1.0f, 0.0f, 0.0f, 1.0f};   // a, b, c, d
    float magnitude = 0.0f;
    float fresnel = 0.0f;
    float error = 0.0f;        // the fit's L3 error (Heitz et al. Sec. 5.2), for the record
    double m11 = 1.0, m22 = 1.0, m13 = 0.0;   // the fit's parameters (the next entry's initial guess)
};

// Table coordinates: row r holds alpha = max((r / (size - 1))^2, kAlphaMin) (uniform in sqrt(alpha)); column c
// holds cos(theta) = max(1 - (c / (size - 1))^2, kCosThetaMin) (uniform in sqrt(1 - cos theta), dense at grazing
// angles where the lobe changes fastest).
constexpr double kAlphaMin = 1e-3;
constexpr double kCosThetaMin = 1e-3;
double rowAlpha(int row, int size);
double columnCosTheta(int column, int size);

struct FitSettings {
    int size = 32;                // rows = columns
    int integralSamples = 128;    // per axis, for the lobe integrals (the horizon cuts the strata: ~0.5 % at 128)
    int errorSamples = 12;        // per axis and sample set (LTC, BRDF) for the fit error
    int maxIterations = 40;       // Nelder-Mead (from the neighbour's fit: converged to ~1e-4 in the parameters)
};

// Fits one entry; `guess` is the previous entry's fit (the march of Heitz et al.'s fitting code: rough to smooth,
// normal to grazing). Isotropic at theta = 0 (m22 = m11, m13 = 0).
Entry fitEntry(Ndf ndf, Lobe lobe, double alpha, double cosTheta, const Entry* guess, const FitSettings& settings);
// The fit's L3 error of `ltc` against the normalized lobe.
double fitError(Ndf ndf, Lobe lobe, double alpha, const glm::dvec3& v, double magnitude, const Ltc& ltc, int samples);

// A whole table, row-major by (row = alpha, column = theta).
std::vector<Entry> fitTable(Ndf ndf, Lobe lobe, const FitSettings& settings);

}  // namespace glimmer::ltcfit
