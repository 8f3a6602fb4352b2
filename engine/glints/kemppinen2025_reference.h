// CPU reference of Kemppinen et al. 2025 ("Evaluating and Sampling Glinty NDFs in Constant Time"): the same
// formulas as shaders/glints/kemppinen2025_core.glsl, kemppinen2025.glsl and kemppinen2025_sampling.glsl,
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
};
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
