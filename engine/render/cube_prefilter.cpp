#include "render/cube_prefilter.h"

#include <algorithm>

namespace glimmer {

namespace {
constexpr int kLocalSize = 8;     // work-group edge of shaders/env/prefilter.comp and radiance_centroid.comp
constexpr int kRootFace = 4;      // the quadtree's roots: the texels of the mip whose faces are 4 x 4
// Texels straddling the horizon are split while wider than this (radians at the face centre): 1/8 of a face, so
// they end at 1/16 of a face (with 1/32 the wide levels changed by under 1%).
constexpr float kHorizonWidth = 2.0f / 16.0f;
// Levels 1 .. this are computed at half their face size and upsampled bilinearly: their lobes (alpha 0.04 and 0.16)
// still span about 2 and 7 texels there (sigma of the lobe in l ~ sqrt(2) alpha for Beckmann), they cost four
// times less, and the upsampling moved the worst texel against quadrature by under 1% (docs/environment.md).
constexpr int kHalfResolutionLevels = 2;
int groups(int size) { return (size + kLocalSize - 1) / kLocalSize; }
int mipCount(int size) {
    int levels = 1;
    while ((size >> levels) > 0) ++levels;
    return levels;
}
}  // namespace

CubePrefilter::CubePrefilter(const std::filesystem::path& shaderRoot)
    : program_(shaderRoot, {"env/prefilter", {{GL_COMPUTE_SHADER, "env/prefilter.comp"}}}),
      upsampleProgram_(shaderRoot, {"env/upsample_cube", {{GL_COMPUTE_SHADER, "env/upsample_cube.comp"}}}),
      sumsProgram_(shaderRoot, {"env/radiance_centroid", {{GL_COMPUTE_SHADER, "env/radiance_centroid.comp"}}}) {}

int CubePrefilter::rootMip(int faceSize) {
    int mip = 0;
    while ((faceSize >> (mip + 1)) >= kRootFace) ++mip;
    return mip;
}

void CubePrefilter::buildSums(GLuint sourceLayers, int faceSize) {
    if (sumsSize_ != faceSize) {
        for (gl::Texture* chain : {&weighted_, &centroids_}) {
            GLuint array = 0;
            glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &array);
            *chain = gl::Texture(array);
            glTextureStorage3D(array, mipCount(faceSize), GL_RGBA32F, faceSize, faceSize, 6);
            glTextureParameteri(array, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
            glTextureParameteri(array, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
        sumsSize_ = faceSize;
    }
    sumsProgram_.use();
    glBindTextureUnit(0, sourceLayers);
    glBindImageTexture(0, weighted_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(1, centroids_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUniform1i(0, faceSize);
    glDispatchCompute(groups(faceSize), groups(faceSize), 6);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glGenerateTextureMipmap(weighted_.id());
    glGenerateTextureMipmap(centroids_.id());
}

void CubePrefilter::run(GLuint source, int faceSize, GLuint target, int levels, int firstLayer, unsigned ndfMask) {
    // The source cube's faces as a 2D array, so the walk can texelFetch a given face, texel and mip.
    GLuint layers = 0;
    glGenTextures(1, &layers);
    glTextureView(layers, GL_TEXTURE_2D_ARRAY, source, GL_RGBA32F, 0, GLuint(mipCount(faceSize)), 0, 6);
    gl::Texture sourceLayers(layers);
    buildSums(sourceLayers.id(), faceSize);

    program_.use();
    glBindTextureUnit(0, weighted_.id());
    glBindTextureUnit(1, centroids_.id());
    glUniform1i(3, rootMip(faceSize));
    glUniform1i(4, faceSize);
    glUniform1f(5, kRefine);
    glUniform1i(6, firstLayer);
    glUniform1f(7, kHorizonWidth);
    for (int level = 1; level < levels; ++level) {
        int size = std::max(faceSize >> level, 1);
        bool half = level <= kHalfResolutionLevels && size >= 2 * kLocalSize;
        int computed = half ? size / 2 : size;
        gl::Texture scratch;
        if (half) {
            GLuint array = 0;
            glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &array);
            scratch = gl::Texture(array);
            glTextureStorage3D(array, 1, GL_RGBA32F, computed, computed, 12);
            glTextureParameteri(array, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTextureParameteri(array, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glTextureParameteri(array, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTextureParameteri(array, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        }
        program_.use();
        if (half) glBindImageTexture(0, scratch.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        else glBindImageTexture(0, target, level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glUniform1i(0, computed);
        glUniform1f(1, levelAlpha(level, levels));
        glUniform1i(6, half ? 0 : firstLayer);
        for (int ndf = 0; ndf < 2; ++ndf) {
            if (!(ndfMask & (1u << ndf))) continue;
            glUniform1i(2, ndf);
            glDispatchCompute(groups(computed), groups(computed), 6);
        }
        if (!half) continue;
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        upsampleProgram_.use();
        glBindTextureUnit(0, scratch.id());
        glBindImageTexture(0, target, level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glUniform1i(0, size);
        glUniform1i(2, firstLayer);
        for (int ndf = 0; ndf < 2; ++ndf) {
            if (!(ndfMask & (1u << ndf))) continue;
            glUniform1i(1, ndf);
            glDispatchCompute(groups(size), groups(size), 6);
        }
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindTextureUnit(0, weighted_.id());   // the walk's inputs again for the next level
        glBindTextureUnit(1, centroids_.id());
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace glimmer
