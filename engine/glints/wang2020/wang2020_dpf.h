// Wang, Deng & Holzschuch 2020, directional probability function (DPF): P(i, o, gamma), the probability that a
// particle with a Beckmann-distributed normal reflects light from i into the cone of half-angle gamma around o
// (Sec. 3.2, Eq. 6). Isotropic, so it is tabulated over (theta_i, theta_o, phi_o - phi_i) as in the paper
// (Table 2: 90 x 90 x 180, 1 degree cells; phi covers [0, 180] by symmetry).
//  - generation (Sec. 4.4, CPU, once): one table per roughness sample 0.02 .. 1.0 at gamma = 1 degree, cached on
//    disk, multithreaded;
//  - extraction + accumulation (Sec. 4.4): interpolate the two tables bracketing the material roughness, then
//    accumulate the 1-degree table over the cone of the material's search angle gamma.
#pragma once
#include <array>
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace glimmer::wang2020 {

constexpr float kPi = 3.14159265358979f;
constexpr float kDegree = kPi / 180.0f;
// Paper Sec. 4.4: "We sample the surface roughness with 0.02, 0.04, 0.1, 0.2, 0.4, 0.6, 0.8, 1.0".
constexpr std::array<float, 8> kRoughnessSamples = {0.02f, 0.04f, 0.1f, 0.2f, 0.4f, 0.6f, 0.8f, 1.0f};
constexpr float kBaseGamma = 1.0f * kDegree;  // generation cone half-angle (Sec. 4.4)

// The distribution of the particle normals. The paper uses Beckmann; Glimmer's materials are GGX by default, and a
// Beckmann DPF under a GGX material puts 24-29 % more of the highlight's energy near its centre than the GGX
// reference (README "The glint material", wang2020's mean), so the tables follow the material's NDF.
enum class ParticleNdf { Beckmann, Ggx };
const char* particleNdfName(ParticleNdf ndf);

struct DpfResolution {
    int thetaI = 90, thetaO = 90, phi = 180;  // paper: 90 x 90 x 180
    size_t size() const { return size_t(thetaI) * thetaO * phi; }
};

// One DPF table: value(ti, to, p) for theta_i, theta_o in [0, 90) degrees, phi_o - phi_i in [0, 180] degrees,
// cell centres (k + 0.5) * step. Layout: phi fastest, then theta_o, then theta_i (matches a 3D texture with
// x = phi, y = theta_o, z = theta_i).
struct DpfTable {
    DpfResolution res;
    float gamma = kBaseGamma;
    std::vector<float> values;
    float at(int ti, int to, int p) const { return values[(size_t(ti) * res.thetaO + to) * res.phi + p]; }
    // Trilinear lookup with clamping at the borders (the GLSL side does the same with a linear 3D texture).
    float lookup(float thetaI, float thetaO, float phi) const;
    float lookup(glm::vec3 wi, glm::vec3 wo) const;  // shading-frame directions
};

// Beckmann D (normalized so that the projected area integrates to 1) and the reflection density of o given i:
// p(o | i) = D(h) (h.n) / (4 |i.h|) (particles' normals distributed by D(m)(m.n), Jakob et al. 2014).
float beckmannD(glm::vec3 m, float alpha);
float ggxD(glm::vec3 m, float alpha);
float reflectionDensity(glm::vec3 wi, glm::vec3 wo, float alpha, ParticleNdf ndf = ParticleNdf::Beckmann);

// Direction for table coordinates (theta, phi): wi at phi = 0, wo at phi.
glm::vec3 sphericalDirection(float theta, float phi);

// P(i, o, gamma) by quadrature of the reflection density over the cone (the limit of counting infinitely many
// particles, the WWH18 counting estimator's expectation). `rings` concentric rings.
float dpfByQuadrature(glm::vec3 wi, glm::vec3 wo, float alpha, float gamma, int rings,
                      ParticleNdf ndf = ParticleNdf::Beckmann);

// Generates the table of one roughness at gamma = 1 degree with `threads` std::threads.
DpfTable generateDpf(float alpha, DpfResolution res, int threads, ParticleNdf ndf = ParticleNdf::Beckmann);

// The eight tables of the paper's roughness samples, loaded from `cacheDir` when present (file name carries the
// resolution and a format version), generated (progress on the log, time stated) and saved otherwise.
struct DpfSet {
    std::vector<DpfTable> tables;  // one per kRoughnessSamples entry
    double generationMs = 0.0;     // 0 when loaded from the cache
    bool fromCache = false;
};
// Beckmann and GGX sets are cached under different names (Beckmann's keep the names of earlier versions).
DpfSet loadOrGenerateDpfSet(DpfResolution res, const std::filesystem::path& cacheDir, int threads = 0,
                            ParticleNdf ndf = ParticleNdf::Beckmann);
// $GLIMMER_DPF_CACHE, else $XDG_CACHE_HOME/glimmer, else $HOME/.cache/glimmer, else the temp directory.
std::filesystem::path defaultDpfCacheDir();

// DPF extraction (linear interpolation in roughness between the bracketing samples) at gamma = 1 degree.
DpfTable extractDpf(const DpfSet& set, float alpha);
// Accumulation for the search angle gamma: P_gamma(i, o) = integral over the gamma-cone around o of
// P_1deg(i, o') / sigma(1deg) do' (each 1-degree entry is a probability over a 1-degree cone: divided by its solid
// angle it is the reflection density, integrated over the larger cone it is the larger probability).
DpfTable accumulateDpf(const DpfTable& base, float gamma, int threads = 0);

// Solid angle of a cone of half-angle gamma.
inline float coneSolidAngle(float gamma) { return 2.0f * kPi * (1.0f - std::cos(gamma)); }

}  // namespace glimmer::wang2020
