// CPU references for the environment-lighting passes (shaders/env/*.comp, shaders/environment/prefiltered_lookup.glsl): the same
// direction conventions and microfacet terms, evaluated by brute force (quadrature over every cube texel or
// thousands of samples) so tests can check the GPU precomputation and the split-sum result against them.
// Straightforward and slow on purpose; nothing here runs in the renderer (the shared cube conventions are in
// environment/cube_texels.h).
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <vector>

#include "core/image_io.h"
#include "environment/cube_texels.h"

namespace glimmer::envref {

constexpr int kNdfGgx = 0, kNdfBeckmann = 1;   // mirror NDF_GGX / NDF_BECKMANN (shaders/common/constants.glsl)

// Equirectangular mapping (same as shaders/environment/equirect_to_cube.comp): u = 0.5 at -z, growing towards +x;
// v = 0 at the zenith (+y), image rows top-down.
glm::vec2 directionToEquirect(glm::vec3 direction);
glm::vec3 equirectToDirection(glm::vec2 uv);
// Bilinear sample with the texture unit's rules: texel centres at (i + 0.5) / size, u wraps, v clamps.
glm::vec3 sampleEquirect(const ImageF& image, glm::vec3 direction);

// Bilinear lookup of the face texel the direction hits (no filtering across faces; tests avoid seams).
glm::vec3 sampleCube(const CubeImage& cube, glm::vec3 direction);

// Rotation of the environment about +y (env.rotation): world direction -> direction in the map.
glm::vec3 worldToEnvironment(glm::vec3 direction, float rotationDegrees);

// Microfacet terms of shaders/common/brdf.glsl as functions of the cosine to the normal (both NDFs isotropic).
double ndfD(double cosThetaH, double alpha, int ndf);
double smithG1(double cosTheta, double alpha, int ndf);
double schlickWeight(double cosTheta);   // (1 - cos)^5

// Split-sum BRDF table entry (Karis 2013): directional albedo of the specular lobe written f0 * A + B, with
// A = int (1 - Fc) f / F cos, B = int Fc f / F cos over the hemisphere. Brute force: a dense midpoint grid over
// the half-vector hemisphere, denser towards the normal (no sampling; no code shared with the GPU pass).
glm::dvec2 splitSumReference(double nDotV, double alpha, int ndf);

// Prefiltered radiance of the split-sum approximation (Karis 2013, Eq. 3 with n = v = r):
// L(r) = int L(l) D(h) (n.l) dl / int D(h) (n.l) dl over n.l > 0, h = normalize(l + r). Quadrature over every
// texel of `cube`.
glm::dvec3 prefilteredRadianceReference(const CubeImage& cube, glm::vec3 r, double alpha, int ndf);

// The true specular reflection integral int L(l) f_spec(v, l) (n.l) dl (Cook-Torrance D G F / (4 n.l n.v),
// Schlick F with f0), by quadrature over every texel of `cube`. n, v, and cube directions share one frame.
glm::dvec3 specularIntegralReference(const CubeImage& cube, glm::vec3 n, glm::vec3 v, double alpha, int ndf,
                                     glm::vec3 f0);

// Irradiance divided by pi: int L(l) max(n.l, 0) dl / pi (the radiance a white Lambertian surface reflects).
glm::dvec3 diffuseReference(const CubeImage& cube, glm::vec3 n);

}  // namespace glimmer::envref
