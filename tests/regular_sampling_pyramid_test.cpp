// Sec. 3 / Table 1 of "Real-time Rendering of Glossy Materials with Regular Sampling" (CGI 2014): cube-map MIP
// pyramids with box 2x2, Gaussian 4x4 and 6x6 filters on the GPU against the CPU reference, and their build times
// for 256, 512 and 1024 faces (wall clock around glFinish, median of 5; written to test-output).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>

#include <glm/gtc/packing.hpp>

#include "core/clock.h"
#include "core/files.h"
#include "environment/ibl/cube_pyramid.h"
#include "platform/context.h"

namespace glimmer::ibl {
namespace {

namespace fs = std::filesystem;

std::vector<float> readLevel(GLuint cube, int level, int size) {
    std::vector<float> pixels(size_t(size) * size * 4 * 6);
    glGetTextureImage(cube, level, GL_RGBA, GL_FLOAT, GLsizei(pixels.size() * sizeof(float)), pixels.data());
    return pixels;
}

TEST(RegularSamplingPyramid, GpuLevelsMatchTheCpuFilters) {
    auto context = createHeadlessContext(Backend::Egl);
    CubePyramidBuilder builder(defaultShaderDir());
    const int size = 32;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 4.0f);
    std::vector<float> level0(size_t(size) * size * 4 * 6);
    for (float& v : level0) v = glm::unpackHalf1x16(glm::packHalf1x16(u(rng)));   // exactly representable
    for (PyramidFilter filter : {PyramidFilter::Box2, PyramidFilter::Gauss4, PyramidFilter::Gauss6}) {
        SCOPED_TRACE(pyramidFilterName(filter));
        gl::Texture cube = createPyramidCube(size);
        glTextureSubImage3D(cube.id(), 0, 0, 0, 0, size, size, 6, GL_RGBA, GL_FLOAT, level0.data());
        builder.build(cube.id(), size, filter);
        std::vector<float> gpu1 = readLevel(cube.id(), 1, size / 2);
        std::vector<float> gpu2 = readLevel(cube.id(), 2, size / 4);
        double worst = 0.0;
        const size_t face0 = size_t(size) * size * 4, face1 = face0 / 4, face2 = face1 / 4;
        for (int face = 0; face < 6; ++face) {
            std::vector<float> src(level0.begin() + face * face0, level0.begin() + (face + 1) * face0);
            std::vector<float> cpu1 = downsampleCubeFaceReference(src, size, filter);
            // Level 2 from the GPU's (half-float) level 1, so rounding does not accumulate between the two.
            std::vector<float> gpuFace1(gpu1.begin() + face * face1, gpu1.begin() + (face + 1) * face1);
            std::vector<float> cpu2 = downsampleCubeFaceReference(gpuFace1, size / 2, filter);
            for (size_t i = 0; i < face1; ++i) worst = std::max(worst, double(std::abs(cpu1[i] - gpu1[face * face1 + i])));
            for (size_t i = 0; i < face2; ++i) worst = std::max(worst, double(std::abs(cpu2[i] - gpu2[face * face2 + i])));
        }
        EXPECT_LT(worst, 4.0 * 2e-3) << "half-float rounding of values up to 4";
    }
    // The filters differ: a single bright texel spreads over 1, 2x2 and 3x3 children.
    std::vector<float> impulse(size_t(8) * 8 * 4, 0.0f);
    impulse[(3 * 8 + 3) * 4] = 1.0f;
    auto count = [&](PyramidFilter f) {
        std::vector<float> d = downsampleCubeFaceReference(impulse, 8, f);
        int n = 0;
        for (size_t i = 0; i < d.size(); i += 4) n += d[i] > 0.0f;
        return n;
    };
    EXPECT_EQ(count(PyramidFilter::Box2), 1);
    EXPECT_EQ(count(PyramidFilter::Gauss4), 4);
    EXPECT_EQ(count(PyramidFilter::Gauss6), 9);
}

TEST(RegularSamplingPyramid, BuildTimesLikeTable1) {
    auto context = createHeadlessContext(Backend::Egl);
    CubePyramidBuilder builder(defaultShaderDir());
    fs::path dir = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "regular_sampling";
    fs::create_directories(dir);
    FILE* table = std::fopen((dir / "pyramid_times.md").string().c_str(), "w");
    std::fprintf(table, "| filter | 256 | 512 | 1024 |\n|---|---|---|---|\n");
    for (PyramidFilter filter : {PyramidFilter::Box2, PyramidFilter::Gauss4, PyramidFilter::Gauss6}) {
        std::fprintf(table, "| %s |", pyramidFilterName(filter));
        for (int size : {256, 512, 1024}) {
            gl::Texture cube = createPyramidCube(size);
            const float grey[4] = {0.5f, 0.5f, 0.5f, 1.0f};
            glClearTexImage(cube.id(), 0, GL_RGBA, GL_FLOAT, grey);
            builder.build(cube.id(), size, filter);   // warm-up (compilation, allocation)
            glFinish();
            std::vector<double> ms;
            for (int i = 0; i < 5; ++i) {
                Stopwatch clock;
                builder.build(cube.id(), size, filter);
                glFinish();
                ms.push_back(clock.elapsedMs());
            }
            std::sort(ms.begin(), ms.end());
            std::fprintf(table, " %.2f ms |", ms[2]);
            std::printf("pyramid %s %d: %.2f ms\n", pyramidFilterName(filter), size, ms[2]);
            EXPECT_GT(ms[2], 0.0);
        }
        std::fprintf(table, "\n");
    }
    std::fclose(table);
}

}  // namespace
}  // namespace glimmer::ibl
