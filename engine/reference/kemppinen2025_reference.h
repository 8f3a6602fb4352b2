// CPU reference of Kemppinen et al. 2025 ("Evaluating and Sampling Glinty NDFs in Constant Time"): the same
// formulas as shaders/glints/kemppinen2025/kemppinen2025_core.glsl, kemppinen2025.glsl and kemppinen2025_sampling.glsl,
// written plainly in double precision (the hash is the same 32-bit integer function, so the same points come
// out). Used by the tests to check the shaders and to measure energy and sampling statistics.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "core/params.h"

namespace glimmer::kemppinen2025 {

enum Ndf : int { kGgx = 0, kBeckmann = 1 };

// The method's parameters (engine/glints/methods.cpp, entry "kemppinen2025").
struct Params {
    double density = 2e6;           // points per unit UV area
    double microRoughness = 0.01;   // alpha*
    double filterSize = 0.7;        // f
    int neighbors = 4;              // k: 4 or 16
    double glintAnisotropy = 1.0;   // a: A* = diag(1/sqrt(a), sqrt(a))
    double roughnessAnisotropy = 1.0;
    double colorVariation = 0.0;
    bool triplanar = false;
    bool piCovariance = true;       // angular_covariance: d = pi D(h) (authors' code) or D(h)
    bool authorsLod = true;         // lod: log2(f max|J_i| sqrt(N)) + 2^f (authors' code) or log2(6 sigma sqrt(N))
};
// alpha* as it enters Sigma_a = d (alpha* A*^-1)^2: with d = pi D(h) the lobe is sqrt(pi) wider than with D(h).
double glintWidthScale(const Params& params);
// Reads the values (missing keys take the table's defaults).
Params paramsFrom(const ParamValues& values);

// What a pixel provides (GlintSurface): UV and its screen derivatives, roughness, NDF, density scale; for the
// triplanar mode the world position, its screen derivatives on the tangent plane and the normal.
struct Surface {
    glm::dvec2 uv{0.0}, duvdx{0.0}, duvdy{0.0};
    double alpha = 0.3;
    int ndf = kGgx;
    double densityScale = 1.0;
    glm::dvec3 position{0.0}, dPdx{0.0}, dPdy{0.0}, normal{0.0, 0.0, 1.0};
};

// Smooth NDFs with (alpha_x, alpha_y) and the prior-space mappings T and T^-1 (Sec. 3.2.1-3.2.2).
double smoothD(const glm::dvec3& h, const glm::dvec2& alpha, int ndf);
glm::dvec2 toPrior(const glm::dvec3& h, const glm::dvec2& alpha, int ndf);
glm::dvec3 fromPrior(const glm::dvec2& x, const glm::dvec2& alpha, int ndf);
// (alpha_x, alpha_y) from the material alpha and the roughness anisotropy.
glm::dvec2 splitAlpha(double alpha, double roughnessAnisotropy);

// The implicit grid's point in a cell (Sec. 3.3.1): jitters, roulette number, hue.
struct GridPoint {
    glm::dvec2 spatial, angular;
    double roulette, hue;
};
GridPoint gridPoint(glm::ivec2 spatialCell, glm::ivec2 angularCell, int level, int process);
uint32_t hashComponent(glm::ivec2 spatialCell, glm::ivec2 angularCell, int level, int process, int component);

double roulette(double r, double w);                  // Eq. 8
glm::dvec3 glintColor(double hue, double variation);  // Sec. 3.3.6, mean exactly white
double intervalMass(double x, double sigma, double lo, double hi);

// Per-pixel part of Algorithm 1 (levels, spatial filter), one entry per point process.
struct Process {
    double weight = 1.0;
    glm::dvec2 xs{0.0};          // A* uv (or the triplanar plane coordinates)
    glm::dmat2 covariance{1.0};  // Sigma_s in x_s units
    double lambda = 0.0;
};
struct PixelSetup {
    bool hasGlints = true;
    double density = 0.0, resolution = 0.0;
    glm::dvec2 alpha{0.3}, angularStretch{1.0};
    int processCount = 1;
    Process process[3];
};
PixelSetup setupPixel(const Params& params, const Surface& surface);

// The filtered glinty NDF D*^f(x, h) (Eq. 11, Algorithm 1) in RGB; h in the shading frame. Adds the number of
// Gaussian-pair evaluations to *gaussianCount when given.
glm::dvec3 filteredNdf(const Params& params, const Surface& surface, const glm::dvec3& h,
                       int* gaussianCount = nullptr);
glm::dvec3 filteredNdf(const Params& params, const PixelSetup& pixel, int ndf, const glm::dvec3& h,
                       int* gaussianCount = nullptr);

}  // namespace glimmer::kemppinen2025

namespace glimmer::kemppinen2025 {

// ---- Importance sampling of D*^f (Sec. 3.3.5, Algorithm 2), CPU twin of kemppinen2025_sampling.glsl.
// One sample: a process (triplanar weight), a level (lambda's roulette, lines 4-6), then with probability
// rho_l a defensive sample of the smooth NDF (uniform prior), otherwise x_a uniform over the prior square
// (line 2; the square rather than the disk keeps the block probabilities exact), reservoir sampling over the
// terms of the block B(x_a) (lines 9-15) with weights R N_s m_t(B) Luminance(c), and a truncated Gaussian
// inside B for the chosen term (line 14). The pdf is exact: it sums over every block that contains the sample.
struct HalfVectorSample {
    glm::dvec3 h{0.0, 0.0, 1.0};
    glm::dvec2 prior{0.5};   // the sample in prior space x_a
    double pdf = 0.0;        // solid-angle pdf of h (0: no sample, e.g. outside U)
};

// A deterministic stream of uniform numbers (the GLSL twin uses the same integer steps).
struct SamplerRng {
    uint32_t state;
    explicit SamplerRng(uint32_t seed);
    double next();
};

HalfVectorSample sampleHalfVector(const Params& params, const PixelSetup& pixel, int ndf, SamplerRng& rng);
// Density of the sampler in prior space (x_a) and over solid angle (h).
double samplePriorPdf(const Params& params, const PixelSetup& pixel, int ndf, const glm::dvec2& xa);
double sampleSolidAnglePdf(const Params& params, const PixelSetup& pixel, int ndf, const glm::dvec3& h);
// |J_T|: prior area per solid angle at h (GGX 1 / (8 ax ay |M^T h|^3), Beckmann pi D cos / 4).
double priorJacobian(const glm::dvec3& h, const glm::dvec2& alpha, int ndf);
// The defensive branch: half vectors with density D(h) h.z over solid angle (anisotropic alpha), and that density
// in prior space, D(h) h.z / |J_T(h)| at h = T^-1(xa) (0 outside U).
glm::dvec3 sampleSmoothNdfCos(const glm::dvec2& alpha, int ndf, double u1, double u2);
double defensivePriorPdf(const glm::dvec2& xa, const glm::dvec2& alpha, int ndf);
// Probability of the defensive (smooth-NDF) branch at a level: the share of a lobe at the NDF peak that falls
// outside the k-neighbourhood, at least 0.1.
double defensiveProbability(const Params& params, const PixelSetup& pixel, int ndf, int level);

}  // namespace glimmer::kemppinen2025
