#include "environment/ibl/cube_pyramid.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace glimmer::ibl {

PyramidFilter parsePyramidFilter(const std::string& name) {
    if (name == "box") return PyramidFilter::Box2;
    if (name == "gauss4") return PyramidFilter::Gauss4;
    if (name == "gauss6") return PyramidFilter::Gauss6;
    throw Error("pyramid filter: unknown '" + name + "' (known: box, gauss4, gauss6)");
}

const char* pyramidFilterName(PyramidFilter filter) {
    switch (filter) {
        case PyramidFilter::Box2: return "box";
        case PyramidFilter::Gauss4: return "gauss4";
        case PyramidFilter::Gauss6: return "gauss6";
    }
    return "?";
}

CubePyramidBuilder::CubePyramidBuilder(const std::filesystem::path& shaderRoot, GLenum format)
    : program_(shaderRoot, {"ibl/cube_pyramid",
                            {{GL_COMPUTE_SHADER, "environment/ibl/cube_pyramid.comp"}},
                            {format == GL_RGBA32F ? "PYRAMID_FORMAT rgba32f" : "PYRAMID_FORMAT rgba16f"}}),
      format_(format) {}

gl::Texture createPyramidCube(int faceSize, GLenum format) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
    int levels = 1 + int(std::floor(std::log2(double(faceSize))));
    glTextureStorage2D(id, levels, format, faceSize, faceSize);
    return gl::Texture(id);
}

void CubePyramidBuilder::build(GLuint cube, int faceSize, PyramidFilter filter) {
    program_.use();
    glUniform1i(0, int(filter));
    int levels = 1 + int(std::floor(std::log2(double(faceSize))));
    for (int level = 1; level < levels; ++level) {
        int size = std::max(1, faceSize >> level);
        glBindImageTexture(0, cube, level - 1, GL_TRUE, 0, GL_READ_ONLY, format_);
        glBindImageTexture(1, cube, level, GL_TRUE, 0, GL_WRITE_ONLY, format_);
        glDispatchCompute(GLuint((size + 7) / 8), GLuint((size + 7) / 8), 6);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    }
}

std::vector<float> downsampleCubeFaceReference(const std::vector<float>& face, int size, PyramidFilter filter) {
    const int kernel = int(filter);
    auto weight = [&](int k) {
        if (kernel == 4) return (k == 0 || k == 3) ? 1.0 / 8.0 : 3.0 / 8.0;
        if (kernel == 6) return k == 0 || k == 5 ? 1.0 / 32.0 : (k == 1 || k == 4 ? 5.0 / 32.0 : 10.0 / 32.0);
        return 0.5;
    };
    const int half = std::max(1, size / 2);
    const int first = 1 - kernel / 2;
    std::vector<float> out(size_t(half) * half * 4);
    for (int y = 0; y < half; ++y)
        for (int x = 0; x < half; ++x)
            for (int c = 0; c < 4; ++c) {
                double sum = 0.0;
                for (int ky = 0; ky < kernel; ++ky)
                    for (int kx = 0; kx < kernel; ++kx) {
                        int sx = std::clamp(2 * x + first + kx, 0, size - 1);
                        int sy = std::clamp(2 * y + first + ky, 0, size - 1);
                        sum += weight(kx) * weight(ky) * face[(size_t(sy) * size + sx) * 4 + c];
                    }
                out[(size_t(y) * half + x) * 4 + c] = float(sum);
            }
    return out;
}

}  // namespace glimmer::ibl
