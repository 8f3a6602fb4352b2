// MIP pyramids of cube maps with the filters of Sec. 3 / Table 1 of "Real-time Rendering of Glossy Materials with
// Regular Sampling" (CGI 2014): box 2x2, Gaussian 4x4 and Gaussian 6x6 (shaders/environment/ibl/cube_pyramid.comp). Used for
// Table 1, the per-object environment maps of Sec. 3 (RGBA16F) and ibl.pyramid's re-filtered environment (RGBA32F).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"

namespace glimmer::ibl {

enum class PyramidFilter { Box2 = 2, Gauss4 = 4, Gauss6 = 6 };
PyramidFilter parsePyramidFilter(const std::string& name);   // box | gauss4 | gauss6; Error otherwise
const char* pyramidFilterName(PyramidFilter filter);

class CubePyramidBuilder {
public:
    // format: GL_RGBA16F (per-object maps) or GL_RGBA32F (filtered copies of the environment source).
    explicit CubePyramidBuilder(const std::filesystem::path& shaderRoot, GLenum format = GL_RGBA16F);
    // Fills levels 1.. of `cube` (RGBA16F, faceSize x faceSize at level 0) from level 0.
    void build(GLuint cube, int faceSize, PyramidFilter filter);

private:
    gl::Program program_;
    GLenum format_;
};

// A cube with a full mip chain.
gl::Texture createPyramidCube(int faceSize, GLenum format = GL_RGBA16F);

// CPU reference of one level step for one face (RGBA floats, row-major): the same taps and edge clamping.
std::vector<float> downsampleCubeFaceReference(const std::vector<float>& face, int size, PyramidFilter filter);

}  // namespace glimmer::ibl
