// The split-sum specular prefilter of one source cube map into roughness levels held in cube-map arrays
// (shaders/environment/prefilter.comp): shared by the distant environment (environment/environment.cpp) and the reflection
// probes (render/probes/reflection_probes.cpp), so both filter lobes the same way.
// A level is one roughness written to one mip and layer of a target array (see Level). Each is a quadrature over
// the source's texels along a quadtree of its mips (fine near the lobe, coarse in the tails), weighted at each
// texel's radiance centroid: exact for lamps of a few texels, where sampling was not.
// RGBA are all filtered: the probes keep their sky coverage in alpha (the environment's alpha is 1).
#pragma once
#include <glad/gl.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "gl/program.h"

namespace glimmer {

class CubePrefilter {
public:
    explicit CubePrefilter(const std::filesystem::path& shaderRoot);
    // A source texel is split while its width exceeds kRefine x max(its angle to the lobe's axis, the lobe's width
    // 2 alpha). Measured against CPU quadrature (tests/environment_test.cpp): see docs/environment.md.
    static constexpr float kRefine = 0.5f;
    // kRefine, or GLIMMER_ENV_PREFILTER_REFINE in [0.25, 8] when set (larger: coarser and faster, ~3.5x at 2 for
    // the environment; for tests of the caches, whose maps' accuracy is not what they judge). The caches key on it.
    static float refine();
    // The mip of a faceSize cube whose texels are the walk's roots (4 x 4 per face, or level 0 if smaller).
    static int rootMip(int faceSize);
    static float levelAlpha(int level, int levels) {
        float r = float(level) / float(levels - 1);
        return r * r;
    }

    // One roughness to filter into `target` (a cube-map array) at `mip`, whose faces are `size` texels wide;
    // layerFace[ndf] is the layer-face of face 0 for GGX (0) and Beckmann (1). A `computedSize` below `size`
    // filters at that face size and upsamples bilinearly: for lobes that still span about two texels there.
    struct Level {
        float alpha = 0.0f;
        GLuint target = 0;
        int mip = 0, size = 0;
        int layerFace[2] = {0, 6};
        int computedSize = 0;   // 0: size
    };
    // Filters every level for each NDF with bit (1 << ndf) set in `ndfMask`. `source` is a cube map with a full
    // mip chain of faceSize faces. Up to four consecutive levels with the same target, mip and computed size (in
    // ascending alpha) share one walk of the quadtree. Ends with the image/texture barrier.
    void run(GLuint source, int faceSize, const std::vector<Level>& levels, unsigned ndfMask);
    // run() in steps, one walk (group of levels) a step, so a caller can spread it over frames: begin() fills the
    // sums of `source` (which must not change until the job is done, nor may another job of this prefilter run in
    // between), each step() dispatches the next group and returns true once every level is written.
    struct Job {
        GLuint source = 0;
        int faceSize = 0;
        std::vector<Level> levels;
        unsigned ndfMask = 0;
        std::vector<size_t> groupStarts;   // first level of each group, then levels.size()
        size_t nextGroup = 0;
        bool done() const { return nextGroup + 1 >= groupStarts.size(); }
        int groupCount() const { return int(groupStarts.size()) - 1; }
    };
    Job begin(GLuint source, int faceSize, std::vector<Level> levels, unsigned ndfMask);
    bool step(Job& job);
    // Levels 1 .. levels-1 of `target` (a cube-map array whose level 0 has the source's face size, level k holding
    // sqrt(alpha) = k / (levels - 1)) at layer-faces firstLayer + 6 * ndf; level 0 is left to the caller.
    void runMipChain(GLuint source, int faceSize, GLuint target, int levels, int firstLayer, unsigned ndfMask);
    // Writes the faces of cube `sourceCube` of the cube-map array `source`, read at `sourceMip`, into `target`'s
    // `mip` (faces `size` wide) at layer-face `targetLayerFace`, by seamless bilinear lookup at each target texel's
    // centre: an upsampling, or for a 2x downsampling exactly the box mean of the four texels under it.
    void resample(GLuint source, int sourceCube, int sourceMip, GLuint target, int mip, int size, int targetLayerFace);

private:
    // Fills the two sum chains (level 0 from the source, then box mips) for a faceSize source.
    void buildSums(GLuint sourceLayers, int faceSize);

    // The walk compiled for 1, 2 and 4 roughnesses per dispatch (LOBE_ALPHAS).
    gl::Program program1_, program2_, program4_, resampleProgram_, sumsProgram_;
    gl::Texture weighted_;    // 2D array, 6 layers: radiance x solid angle
    gl::Texture centroids_;   // 2D array, 6 layers: rgb luminance x solid angle x direction, a solid angle
    int sumsSize_ = 0;
    gl::Texture scratch_;   // groups computed below their size: one cube per lobe (NDF x kLobeAlphas + i)
    int scratchSize_ = 0;
    static int computedSize(const Level& level) {
        return level.computedSize > 0 ? std::min(level.computedSize, level.size) : level.size;
    }
};

}  // namespace glimmer
