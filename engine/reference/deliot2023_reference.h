// CPU reference of the core math of Deliot & Belcour 2023 (shaders/glints/deliot2023*.glsl): the random-number
// texture, the gated Gaussian binomial approximation (Sec. 6.3, Eq. 16-18), the exact binomial law it approximates,
// the distributed binomial blend between two LOD levels (Sec. 4.2, Eq. 10) and the footprint -> grid selection
// (Sec. 5, 6.1). Tests compare the shaders against these.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "glints/deliot2023/deliot2023_noise.h"

namespace glimmer::deliot2023 {

struct NoisePair {
    float uniform, gaussian;
};
NoisePair unpackNoisePair(uint32_t packed);

// Mirrors of the shader functions (float arithmetic in the same order).
float probAtLeastOne(float N, float p);                       // Eq. 16 (N < 1: N p)
// Eq. 17-18; softGate: the authors' soft gate 1 - smoothstep(P1 - w, P1 + w, u), w = softGateHalfWidth(P1).
float gatedBinomial(float N, float p, float u, float g, bool softGate = false);
float softGateHalfWidth(float P1);   // 0.1 sat(10 P1) sat(10 (1 - P1))

// The law the approximation targets: b(N, p) for integer N; for N < 1 a single trial of probability N p.
struct Moments {
    double mean = 0.0, variance = 0.0, pZero = 0.0;
};
Moments exactBinomialMoments(double N, double p);

// Sec. 4.2: the facets of a footprint of area P between two stratified levels of cell areas P_lo < P_hi
// (P_hi = 4 P_lo) go to both levels with area-linear weights, Eq. 10: w_hi = (P - P_lo)/(P_hi - P_lo).
// Returns the trials given to the lower and upper level for a footprint holding `facets` facets at area ratio
// P / P_lo = areaRatio in [1, 4] (facets of the lower level's cell = facets / areaRatio).
struct LevelSplit {
    double lowerTrials, upperTrials, upperWeight;
};
LevelSplit distributedSplit(double facetsPerLowerCell, double areaRatio);

// Sec. 5 and 6.1: the 4 grids (scale, ratio level, orientation index) and tetrahedral weights chosen for a
// footprint with semi-axes major >= minor, major axis angle phi (radians), and screen-space scale.
struct Grid {
    int lod = 0, ratioLevel = 0, orientation = 0;
    double weight = 0.0;
};
struct GridSelection {
    double lod = 0.0, ratio = 1.0, phi = 0.0;
    std::array<Grid, 4> grids;
};
GridSelection selectGrids(double major, double minor, double phi, double screenScale);
// Cell area in UV of a grid: 4^lod 2^ratioLevel.
double gridCellArea(const Grid& grid);
// Orientation step of a ratio level (radians): 90 degrees / 2^k.
double orientationStep(int ratioLevel);

}  // namespace glimmer::deliot2023
