// CPU references of the three environment-integration estimators of issue 7, for one glossy Kurt lobe
// (Sec. 4 Eq. 2) in the shading frame (x = t, y = b, z = n). The environment is any function of a direction and a
// MIP level, so tests can use analytic environments (exact references) or a CPU copy of a cube map.
//  - regularLobe: Sec. 6-7 pseudo code: pattern half vectors, per-sample MIP (Eq. 14-16), constant pdf (Eq. 17-18).
//  - fisLobe: Colbert & Krivanek 2007 filtered importance sampling with the Kurt sampling (Eq. 6-7, pdf Eq. 10).
//  - quadratureLobe: the integral of Eq. 8 by a dense midpoint rule over the half-vector hemisphere.
#pragma once
#include <glm/glm.hpp>

#include <functional>

#include "environment/ibl/kurt_brdf.h"
#include "environment/ibl/regular_pattern.h"

namespace glimmer::ibl {

using EnvironmentLookup = std::function<glm::dvec3(glm::dvec3 direction, double lod)>;

// Shading-frame directions are passed to `env` unchanged (the tests' frame is the world frame).
glm::dvec3 regularLobe(glm::dvec3 wo, const KurtLobe& lobe, const RegularPattern& pattern,
                       const EnvironmentLookup& env, int faceSize, double mipBias);

// Colbert & Krivanek 2007 (GPU Gems 3, ch. 20): lod = max(0.5 log2(Omega_s / Omega_p) + 1, 0) with
// Omega_s = 1 / (n pdf) and Omega_p the solid angle of a level-0 texel at wi (cube distortion included).
// Samples are the Hammersley points (i / n, radical inverse of i), rotated by `rotation` (Cranley-Patterson).
glm::dvec3 fisLobe(glm::dvec3 wo, const KurtLobe& lobe, int numSamples, glm::dvec2 rotation,
                   const EnvironmentLookup& env, int faceSize, double mipBias);

// Eq. 8 for one lobe, level-0 lookups, a (thetaSteps x phiSteps) midpoint grid over the half vector with the
// Jacobian 4 (wo.h) from half-vector to incident solid angle.
glm::dvec3 quadratureLobe(glm::dvec3 wo, const KurtLobe& lobe, const EnvironmentLookup& env, int thetaSteps,
                          int phiSteps);

double radicalInverse2(unsigned bits);
// Solid angle of a level-0 texel of a cube with faces of `faceSize` texels seen along unit direction d.
double cubeTexelSolidAngleAt(glm::dvec3 d, int faceSize);

}  // namespace glimmer::ibl
