#include "render/cube_prefilter.h"

#include <algorithm>

namespace glimmer {

namespace {
constexpr int kLocalSize = 8;     // work-group edge of shaders/env/prefilter.comp and radiance_centroid.comp
constexpr int kRootFace = 4;      // the quadtree's roots: the texels of the mip whose faces are 4 x 4
// Texels straddling the horizon are split while wider than this (radians at the face centre): 1/8 of a face, so
// they end at 1/16 of a face (with 1/32 the wide levels changed by under 1%).
constexpr float kHorizonWidth = 2.0f / 16.0f;
// runMipChain: levels 1 .. this are computed at half their face size and upsampled bilinearly: their lobes (alpha
// 0.04 and 0.16) still span about 2 and 7 texels there (sigma of the lobe in l ~ sqrt(2) alpha for Beckmann), they
// cost four times less, and the upsampling moved the worst texel against quadrature by under 1% (docs/environment.md).
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
      resampleProgram_(shaderRoot, {"env/resample_cube", {{GL_COMPUTE_SHADER, "env/resample_cube.comp"}}}),
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

void CubePrefilter::resample(GLuint source, int sourceCube, int sourceMip, GLuint target, int mip, int size,
                             int targetLayerFace) {
    resampleProgram_.use();
    glBindTextureUnit(0, source);
    glBindImageTexture(0, target, mip, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUniform1i(0, size);
    glUniform1i(1, sourceCube);
    glUniform1i(2, targetLayerFace);
    glUniform1i(3, sourceMip);
    glDispatchCompute(groups(size), groups(size), 6);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void CubePrefilter::run(GLuint source, int faceSize, const std::vector<Level>& levels, unsigned ndfMask) {
    // The source cube's faces as a 2D array, so the walk can texelFetch a given face, texel and mip.
    GLuint layers = 0;
    glGenTextures(1, &layers);
    glTextureView(layers, GL_TEXTURE_2D_ARRAY, source, GL_RGBA32F, 0, GLuint(mipCount(faceSize)), 0, 6);
    gl::Texture sourceLayers(layers);
    buildSums(sourceLayers.id(), faceSize);

    gl::Texture scratch;   // levels computed below their size: one cube per NDF
    int scratchSize = 0;
    for (const Level& level : levels) {
        int computed = level.computedSize > 0 ? std::min(level.computedSize, level.size) : level.size;
        bool half = computed < level.size;   // upsampled from a scratch array
        if (half && scratchSize != computed) {
            GLuint array = 0;
            glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &array);
            scratch = gl::Texture(array);
            glTextureStorage3D(array, 1, GL_RGBA32F, computed, computed, 12);
            glTextureParameteri(array, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTextureParameteri(array, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glTextureParameteri(array, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTextureParameteri(array, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            scratchSize = computed;
        }
        program_.use();
        glBindTextureUnit(0, weighted_.id());
        glBindTextureUnit(1, centroids_.id());
        glUniform1i(3, rootMip(faceSize));
        glUniform1i(4, faceSize);
        glUniform1f(5, kRefine);
        glUniform1f(7, kHorizonWidth);
        if (half) glBindImageTexture(0, scratch.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        else glBindImageTexture(0, level.target, level.mip, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glUniform1i(0, computed);
        glUniform1f(1, level.alpha);
        for (int ndf = 0; ndf < 2; ++ndf) {
            if (!(ndfMask & (1u << ndf))) continue;
            glUniform1i(2, ndf);
            glUniform1i(6, half ? 6 * ndf : level.layerFace[ndf]);
            glDispatchCompute(groups(computed), groups(computed), 6);
        }
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        if (!half) continue;
        for (int ndf = 0; ndf < 2; ++ndf)
            if (ndfMask & (1u << ndf))
                resample(scratch.id(), ndf, 0, level.target, level.mip, level.size, level.layerFace[ndf]);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

void CubePrefilter::runMipChain(GLuint source, int faceSize, GLuint target, int levels, int firstLayer,
                                unsigned ndfMask) {
    std::vector<Level> chain;
    for (int k = 1; k < levels; ++k) {
        Level level;
        level.alpha = levelAlpha(k, levels);
        level.target = target;
        level.mip = k;
        level.size = std::max(faceSize >> k, 1);
        level.layerFace[0] = firstLayer;
        level.layerFace[1] = firstLayer + 6;
        if (k <= kHalfResolutionLevels && level.size >= 2 * kLocalSize) level.computedSize = level.size / 2;
        chain.push_back(level);
    }
    run(source, faceSize, chain, ndfMask);
}

}  // namespace glimmer
