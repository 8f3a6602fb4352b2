// CPU reference of the Monte Carlo IBL modes `ndf-is` and `glint-is` (shaders/environment/ibl/microfacet_sampling.glsl,
// ndf_is.glsl, glint_is.glsl): the same random streams (identical 32-bit integer steps), the same samplers and the
// same one-sample estimator of the reflected environment radiance, in double precision, with the environment and
// the NDF given as functions. Tests run it sample by sample against the shader and average it against quadrature.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <functional>

#include "reference/kemppinen2025_reference.h"

namespace glimmer::iblref {

// ---- Random streams (iblHash, iblSampleSeed, iblRandom).
uint32_t hash(uint32_t v);
uint32_t sampleSeed(glm::ivec2 pixel, uint32_t sampleIndex, uint32_t seed);
struct Rng {
    uint32_t state;
    double next();   // PCG-RXS-M-XS 32: 24-bit uniform in [0, 1)
};

// ---- Samplers (shading frame, z = normal).
// Half vector with density D(h) h.z (Walter et al. 2007, Eq. 28-29 Beckmann, 35-36 GGX); ndf 0 GGX, 1 Beckmann.
glm::dvec3 sampleSmoothNdf(double u1, double u2, double alpha, int ndf);
double smoothNdfPdf(const glm::dvec3& h, double alpha, int ndf);
glm::dvec3 sampleCosine(double u1, double u2);

// What one pixel contributes to the estimator. frame columns: world-space tangent, bitangent, normal.
struct ShadingPoint {
    glm::dmat3 frame{1.0};
    glm::dvec3 wo{0.0, 0.0, 1.0};   // towards the eye, shading frame
    double alpha = 0.3;
    int ndf = 0;
    glm::dvec3 f0{0.04}, diffuseAlbedo{0.0};
};
using RadianceFn = std::function<glm::dvec3(const glm::dvec3& worldDirection)>;
using NdfFn = std::function<glm::dvec3(const glm::dvec3& h)>;   // the NDF in f (RGB), shading-frame h

// D G F |wo.h| / (|wo.n| pdfH) x L(reflect(-wo, h)): one specular estimate for h drawn with density pdfH.
glm::dvec3 specularEstimate(const ShadingPoint& p, const NdfFn& ndf, const glm::dvec3& h, double pdfH,
                            const RadianceFn& environment);
// The integral the estimators converge to, int f_spec(wi, wo) |wi.n| L(wi) dwi, as an integral over half vectors
// (dwi = 4 |wo.h| dh) by midpoint quadrature in the prior space of the smooth NDF (where a glint lobe of width
// alpha* sqrt(D) spans `grid` / (alpha* ...) cells): grid x grid points of the unit disk mapped by T^-1.
glm::dvec3 specularIntegral(const ShadingPoint& p, const NdfFn& ndf, const RadianceFn& environment, int grid);

enum class Mode { NdfIs, GlintIs };
// The glinty part of a pixel under glint-is (kemppinen2025 only): parameters and per-pixel setup.
struct GlintPixel {
    const kemppinen2025::Params* params = nullptr;
    const kemppinen2025::PixelSetup* setup = nullptr;
};
// iblRadiance of the mode for one pixel and accumulation index: the diffuse (cosine) and specular sample.
// `glinty`: the material uses the glint NDF `ndf`; otherwise D is the smooth NDF (and glint-is samples it).
glm::dvec3 estimate(Mode mode, const ShadingPoint& p, bool glinty, const NdfFn& ndf, const GlintPixel& glint,
                    glm::ivec2 pixel, uint32_t sampleIndex, uint32_t seed, const RadianceFn& environment);

}  // namespace glimmer::iblref
