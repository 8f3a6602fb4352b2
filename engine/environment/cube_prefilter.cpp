#include "environment/cube_prefilter.h"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "common/bindings.glsl"
#include "core/log.h"

namespace glimmer {

namespace {
constexpr int kLocalSize = 8;     // work-group edge of shaders/environment/prefilter.comp and radiance_centroid.comp
constexpr int kRootFace = 4;      // the quadtree's roots: the texels of the mip whose faces are 4 x 4
// Texels straddling the horizon are split while wider than this (radians at the face centre): 1/8 of a face, so
// they end at 1/16 of a face; a finer split no longer changes the wide levels (docs/measurements.md).
constexpr float kHorizonWidth = 2.0f / 16.0f;
// runMipChain: levels 1 .. this are computed at half their face size and upsampled bilinearly: their lobes (alpha
// 0.04 and 0.16) still span about 2 and 7 texels there (sigma of the lobe in l ~ sqrt(2) alpha for Beckmann), so the
// upsampling keeps them against quadrature (docs/measurements.md) at a quarter of the cost.
constexpr int kHalfResolutionLevels = 2;
constexpr int kLobeAlphas = 4;     // roughnesses per walk of shaders/environment/prefilter.comp (u_alphas)
int groups(int size) { return (size + kLocalSize - 1) / kLocalSize; }
int mipCount(int size) {
    int levels = 1;
    while ((size >> levels) > 0) ++levels;
    return levels;
}
}  // namespace

CubePrefilter::CubePrefilter(const std::filesystem::path& shaderRoot)
    : program1_(shaderRoot, {"env/prefilter", {{GL_COMPUTE_SHADER, "environment/prefilter.comp"}}, {"LOBE_ALPHAS 1"}}),
      program2_(shaderRoot, {"env/prefilter", {{GL_COMPUTE_SHADER, "environment/prefilter.comp"}}, {"LOBE_ALPHAS 2"}}),
      program4_(shaderRoot, {"env/prefilter", {{GL_COMPUTE_SHADER, "environment/prefilter.comp"}}, {"LOBE_ALPHAS 4"}}),
      resampleProgram_(shaderRoot, {"env/resample_cube", {{GL_COMPUTE_SHADER, "environment/resample_cube.comp"}}}),
      sumsProgram_(shaderRoot, {"env/radiance_centroid", {{GL_COMPUTE_SHADER, "environment/radiance_centroid.comp"}}}) {}

float CubePrefilter::refine() {
    const char* text = std::getenv("GLIMMER_ENV_PREFILTER_REFINE");
    if (!text || !*text) return kRefine;
    char* end = nullptr;
    const float value = std::strtof(text, &end);
    if (*end != '\0' || !(value >= 0.25f && value <= 8.0f)) {
        log::warn("GLIMMER_ENV_PREFILTER_REFINE='", std::string(text).substr(0, 32),
                  "' is not a number in [0.25, 8]; using ", kRefine);
        return kRefine;
    }
    return value;
}

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
    glBindTextureUnit(UNIT_ENV_INPUT, sourceLayers);
    glBindImageTexture(IMAGE_ENV_WEIGHTED, weighted_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(IMAGE_ENV_CENTROID, centroids_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUniform1i(0, faceSize);
    glDispatchCompute(groups(faceSize), groups(faceSize), 6);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glGenerateTextureMipmap(weighted_.id());
    glGenerateTextureMipmap(centroids_.id());
}

void CubePrefilter::resample(GLuint source, int sourceCube, int sourceMip, GLuint target, int mip, int size,
                             int targetLayerFace) {
    resampleProgram_.use();
    glBindTextureUnit(UNIT_ENV_INPUT, source);
    glBindImageTexture(IMAGE_ENV_OUTPUT, target, mip, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUniform1i(0, size);
    glUniform1i(1, sourceCube);
    glUniform1i(2, targetLayerFace);
    glUniform1i(3, sourceMip);
    glDispatchCompute(groups(size), groups(size), 6);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

CubePrefilter::Job CubePrefilter::begin(GLuint source, int faceSize, std::vector<Level> levels, unsigned ndfMask) {
    // The source cube's faces as a 2D array, so the walk can texelFetch a given face, texel and mip.
    GLuint layers = 0;
    glGenTextures(1, &layers);
    glTextureView(layers, GL_TEXTURE_2D_ARRAY, source, GL_RGBA32F, 0, GLuint(mipCount(faceSize)), 0, 6);
    gl::Texture sourceLayers(layers);
    buildSums(sourceLayers.id(), faceSize);
    Job job{source, faceSize, std::move(levels), ndfMask};
    // Groups: up to kLobeAlphas consecutive levels into the same mip at the same computed size share one walk.
    for (size_t first = 0; first < job.levels.size();) {
        const Level& lead = job.levels[first];
        size_t end = first + 1;
        while (end < job.levels.size() && end - first < size_t(kLobeAlphas) && job.levels[end].target == lead.target &&
               job.levels[end].mip == lead.mip && job.levels[end].size == lead.size &&
               computedSize(job.levels[end]) == computedSize(lead))
            ++end;
        job.groupStarts.push_back(first);
        first = end;
    }
    job.groupStarts.push_back(job.levels.size());
    return job;
}

bool CubePrefilter::step(Job& job) {
    if (job.done()) return true;
    const size_t first = job.groupStarts[job.nextGroup], end = job.groupStarts[job.nextGroup + 1];
    ++job.nextGroup;
    const Level& lead = job.levels[first];
    const int count = int(end - first);
    const int computed = computedSize(lead);
    const bool half = computed < lead.size;   // upsampled from the scratch array
    if (half && scratchSize_ != computed) {   // one cube per lobe (NDF x 4 + i)
        GLuint array = 0;
        glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &array);
        scratch_ = gl::Texture(array);
        glTextureStorage3D(array, 1, GL_RGBA32F, computed, computed, 6 * 2 * kLobeAlphas);
        glTextureParameteri(array, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(array, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(array, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(array, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        scratchSize_ = computed;
    }
    float alphas[kLobeAlphas] = {};
    GLint layerFaces[2 * kLobeAlphas] = {};
    for (int i = 0; i < count; ++i) {
        alphas[i] = job.levels[first + i].alpha;
        for (int ndf = 0; ndf < 2; ++ndf)
            layerFaces[ndf * kLobeAlphas + i] = half ? 6 * (ndf * kLobeAlphas + i) : job.levels[first + i].layerFace[ndf];
    }
    gl::Program& program = count == 1 ? program1_ : count == 2 ? program2_ : program4_;
    program.use();
    glBindTextureUnit(UNIT_ENV_WEIGHTED, weighted_.id());
    glBindTextureUnit(UNIT_ENV_CENTROID, centroids_.id());
    if (half) glBindImageTexture(IMAGE_ENV_OUTPUT, scratch_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    else glBindImageTexture(IMAGE_ENV_OUTPUT, lead.target, lead.mip, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUniform1i(0, computed);
    glUniform4fv(1, 1, alphas);
    glUniform1i(2, GLint(job.ndfMask & 3u));
    glUniform1i(3, rootMip(job.faceSize));
    glUniform1i(4, job.faceSize);
    glUniform1f(5, refine());
    glUniform4iv(6, 2, layerFaces);
    glUniform1f(8, kHorizonWidth);
    glUniform1i(9, count);
    glDispatchCompute(groups(computed), groups(computed), 6);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    if (half)
        for (int i = 0; i < count; ++i)
            for (int ndf = 0; ndf < 2; ++ndf)
                if (job.ndfMask & (1u << ndf))
                    resample(scratch_.id(), ndf * kLobeAlphas + i, 0, lead.target, lead.mip, lead.size,
                             job.levels[first + i].layerFace[ndf]);
    if (!job.done()) return false;
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    return true;
}

void CubePrefilter::run(GLuint source, int faceSize, const std::vector<Level>& levels, unsigned ndfMask) {
    Job job = begin(source, faceSize, levels, ndfMask);
    while (!step(job)) {}
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
