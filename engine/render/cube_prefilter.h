// The split-sum specular prefilter of one source cube map into the levels of a cube-map array
// (shaders/env/prefilter.comp): shared by the distant environment (render/environment.cpp) and the reflection
// probes (render/reflection_probes.cpp), so both hold the same lobes at the same levels.
// Level k holds roughness sqrt(alpha) = k / (levels - 1); level 0 is left to the caller (the unfiltered source).
// RGBA are all filtered: the probes keep their sky coverage in alpha (the environment's alpha is 1).
#pragma once
#include <glad/gl.h>

#include <filesystem>

#include "gl/program.h"

namespace glimmer {

class CubePrefilter {
public:
    explicit CubePrefilter(const std::filesystem::path& shaderRoot);
    // Samples per texel of level k (k >= 1): 32 << k.
    static int samples(int level) { return 32 << level; }
    static float levelAlpha(int level, int levels) {
        float r = float(level) / float(levels - 1);
        return r * r;
    }
    // Writes levels 1 .. levels-1 of `target` (a cube-map array whose level 0 has the source's face size) at
    // layers firstLayer + 6 * ndf + face for each NDF with bit (1 << ndf) set in `ndfMask` (0 GGX, 1 Beckmann).
    // `source` is a cube map with a full mip chain. Ends with the image/texture barrier.
    void run(GLuint source, int faceSize, GLuint target, int levels, int firstLayer, unsigned ndfMask);

private:
    gl::Program program_;
};

}  // namespace glimmer
