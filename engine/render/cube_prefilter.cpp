#include "render/cube_prefilter.h"

namespace glimmer {

namespace {
constexpr int kLocalSize = 8;   // work-group edge of shaders/env/prefilter.comp
int groups(int size) { return (size + kLocalSize - 1) / kLocalSize; }
int mipCount(int size) {
    int levels = 1;
    while ((size >> levels) > 0) ++levels;
    return levels;
}
}  // namespace

CubePrefilter::CubePrefilter(const std::filesystem::path& shaderRoot)
    : program_(shaderRoot, {"env/prefilter", {{GL_COMPUTE_SHADER, "env/prefilter.comp"}}}) {}

void CubePrefilter::run(GLuint source, int faceSize, GLuint target, int levels, int firstLayer, unsigned ndfMask) {
    program_.use();
    glBindTextureUnit(0, source);
    glUniform1i(4, faceSize);
    glUniform1f(5, float(mipCount(faceSize) - 1));
    glUniform1i(6, firstLayer);
    for (int level = 1; level < levels; ++level) {
        int size = std::max(faceSize >> level, 1);
        glBindImageTexture(0, target, level, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glUniform1i(0, size);
        glUniform1f(1, levelAlpha(level, levels));
        glUniform1i(3, samples(level));
        for (int ndf = 0; ndf < 2; ++ndf) {
            if (!(ndfMask & (1u << ndf))) continue;
            glUniform1i(2, ndf);
            glDispatchCompute(groups(size), groups(size), 6);
        }
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

}  // namespace glimmer
