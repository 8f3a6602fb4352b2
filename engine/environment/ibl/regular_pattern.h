// Regular half-vector sample patterns of "Real-time Rendering of Glossy Materials with Regular Sampling" (CGI 2014):
// Sec. 5 (concentric circles around the half-vector pole, Eq. 11-13, anisotropic rejection, budget selection),
// Sec. 6 (per-sample MIP level, Eq. 14-16) and Sec. 7 (constant pdf, Eq. 17-18). Patterns are built here on the
// CPU whenever the material changes and uploaded (engine/ibl/regular_resources.cpp); shaders/environment/ibl/regular.glsl
// mirrors pixelsPerSample and the estimator. Shading frame: x = t, y = b, z = n.
//
// Ring placement (Eq. 12-13 are ambiguous, see docs/regular_sampling.md): nc counts circles, and with s1 the
// pole sample is the first (degenerate) circle: s1 rings sit at theta = k s1, k = 0 .. nc-1 (pole + nc-1 rings);
// with s2 the rings sit at theta = k s2, k = 1 .. nc. theta_0 is the first non-degenerate ring. Ring sizes: see
// RingRule. For nc = 3: s1 gives 1 + 6 + 12 = 19 and s2 4 + 10 + 16 = 30 (Fig. 4) under RingRule::Arc; the
// literal Eq. 13 gives 19 and 4 + 8 + 12 = 24.
#pragma once
#include <glm/glm.hpp>

#include <vector>

namespace glimmer::ibl {

enum class RingSpacing { S1, S2 };   // Eq. 12: s1 = theta_max/(nc+1) with a pole sample, s2 = theta_max/(nc+2)

// How many samples the circles after the first get (Sec. 5, "increased by the ratio of the circumference"):
//  Arc  (default): the circumference grows by 2 pi sin-spacing per circle and samples keep the ring spacing
//        apart: n_i = nearest even of n0 + 2 pi (sin theta_i - sin theta_0) / sin s. Reproduces every count the
//        paper prints: 19 (s1) and 30 (s2) for nc = 3 (Fig. 4), 14 for the isotropic material of Fig. 8.
//  Eq13: Eq. 13 literally, n_i = 2 floor(n0 sin theta_i / (2 sin theta_0) + 1/2): 19 (s1) but 24 (s2).
enum class RingRule { Arc, Eq13 };

struct PatternParams {
    double mx = 0.1, my = 0.1;   // Beckmann roughness of the lobe
    double xi0 = 0.1;            // density threshold (Eq. 11) and rejection threshold
    int nc = 3;                  // number of circles
    RingSpacing spacing = RingSpacing::S1;
    RingRule rule = RingRule::Arc;
};

struct RegularPattern {
    std::vector<glm::dvec3> halfVectors;   // unit, shading frame
    std::vector<int> ringCounts;           // samples kept per circle (pole = 1), in order of theta
    std::vector<bool> ringHalfOffset;      // per circle: the half-sample-offset variant was kept
    double thetaMax = 0.0;                 // Eq. 11
    double pdfConstant = 0.0;              // Eq. 18: p_h = mean of D(h_i)
    PatternParams params;
    int size() const { return int(halfVectors.size()); }
};

// Eq. 11: theta_max = arctan(sqrt(-log xi0) max(mx, my)).
double thetaMax(double xi0, double mx, double my);
// Eq. 13: samples on a circle at theta_i when the first circle at theta_0 holds n0 (nearest multiple of two).
int ringSampleCount(int n0, double thetaI, double theta0);
// RingRule::Arc: n0 + 2 pi (sin theta_i - sin theta_0) / sin(spacing), to the nearest multiple of two.
int ringSampleCountArc(int n0, double thetaI, double theta0, double spacing);

// Sec. 5 (+ Eq. 18). Throws glimmer::Error for invalid parameters (nc < 1, xi0 outside (0,1), m <= 0).
RegularPattern generateRegularPattern(const PatternParams& params);

// Sec. 5, last paragraph: patterns for nc = 1 .. maxCircles with both spacings; the one whose sample count is
// closest to `budget` (ties: fewer samples, then s1).
RegularPattern selectPatternForBudget(double mx, double my, double xi0, int budget, int maxCircles = 24,
                                      RingRule rule = RingRule::Arc);

// Sec. 6, Eq. 14-15 and the area: A = pi u v of the lobe's elliptical cross-section at unit distance, from the
// extreme half vectors at the xi0 border along t and b, reflected about wo. lobeCenter = reflect(-wo, n).
double lobeCrossSectionArea(glm::dvec3 wo, double mx, double my, double xi0);
// Eq. 16: cube texels covered by one sample: A N / (4 n) * (|wi| / |wi|_inf) * 1 / (wi . h), with N texels per
// face and wi expressed in the cube's (world) frame for the distortion term. Returns texels (>= 0).
double pixelsPerSample(double area, int faceTexels, int numSamples, glm::dvec3 wiWorld, double wiDotH);
// MIP level: log4(texels per sample) + bias, clamped at 0.
double mipLevelForSample(double pixels, double bias);

}  // namespace glimmer::ibl
