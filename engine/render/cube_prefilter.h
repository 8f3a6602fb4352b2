// The split-sum specular prefilter of one source cube map into the levels of a cube-map array
// (shaders/env/prefilter.comp): shared by the distant environment (render/environment.cpp) and the reflection
// probes (render/reflection_probes.cpp), so both hold the same lobes at the same levels.
// Level k holds roughness sqrt(alpha) = k / (levels - 1); level 0 is left to the caller (the unfiltered source).
// Each level is a quadrature over the source's texels along a quadtree of its mips (fine near the lobe, coarse in
// the tails), weighted at each texel's radiance centroid: exact for lamps of a few texels, where sampling was not.
// RGBA are all filtered: the probes keep their sky coverage in alpha (the environment's alpha is 1).
#pragma once
#include <glad/gl.h>

#include <filesystem>

#include "gl/program.h"

namespace glimmer {

class CubePrefilter {
public:
    explicit CubePrefilter(const std::filesystem::path& shaderRoot);
    // A source texel is split while its width exceeds kRefine x max(its angle to the lobe's axis, the lobe's width
    // 2 alpha). Measured against CPU quadrature (tests/environment_test.cpp): see docs/environment.md.
    static constexpr float kRefine = 0.5f;
    // The mip of a faceSize cube whose texels are the walk's roots (4 x 4 per face, or level 0 if smaller).
    static int rootMip(int faceSize);
    static float levelAlpha(int level, int levels) {
        float r = float(level) / float(levels - 1);
        return r * r;
    }
    // Writes levels 1 .. levels-1 of `target` (a cube-map array whose level 0 has the source's face size) at
    // layers firstLayer + 6 * ndf + face for each NDF with bit (1 << ndf) set in `ndfMask` (0 GGX, 1 Beckmann).
    // `source` is a cube map with a full mip chain. Ends with the image/texture barrier.
    void run(GLuint source, int faceSize, GLuint target, int levels, int firstLayer, unsigned ndfMask);

private:
    // Fills the two sum chains (level 0 from the source, then box mips) for a faceSize source.
    void buildSums(GLuint sourceLayers, int faceSize);

    gl::Program program_, upsampleProgram_, sumsProgram_;
    gl::Texture weighted_;    // 2D array, 6 layers: radiance x solid angle
    gl::Texture centroids_;   // 2D array, 6 layers: rgb luminance x solid angle x direction, a solid angle
    int sumsSize_ = 0;
};

}  // namespace glimmer
