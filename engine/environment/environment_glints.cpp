#include "environment/environment_glints.h"

#include <chrono>
#include <cstring>

#include "common/bindings.glsl"
#include "environment/ibl/ibl_modes.h"

namespace glimmer {
namespace {

constexpr GLsizeiptr kHeaderBytes = 64;     // levels[2], range, info (std430; shaders/environment/glint_levels.comp)
constexpr int kMaxGroups = 1024;            // first-pass workgroups: (kFaceSize / 16)^2 x 6 = 96

gl::Texture cubeArray(int size, int levels, int layerFaces) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &id);
    glTextureStorage3D(id, levels, GL_RGBA32F, size, size, layerFaces);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return gl::Texture(id);
}

double elapsedMs(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

EnvironmentGlintSettings environmentGlintSettings(const IblMode& mode, const std::map<std::string, float>& values) {
    EnvironmentGlintSettings settings;
    settings.levels = 0;
    for (const ParamSpec& spec : mode.params) {
        if (spec.name == "glint_levels") settings.levels = int(paramOr(values, spec) + 0.5f) == 2 ? 8 : int(paramOr(values, spec) + 0.5f) == 1 ? 4 : 0;
        if (spec.name == "glint_black_level") settings.blackLevel = paramOr(values, spec);
    }
    return settings;
}

EnvironmentGlints::EnvironmentGlints(std::filesystem::path shaderRoot) : shaderRoot_(std::move(shaderRoot)) {
    block_ = gl::createBuffer(kHeaderBytes + kMaxGroups * 8, nullptr);
    std::vector<unsigned char> zero(kHeaderBytes, 0);
    glNamedBufferSubData(block_.id(), 0, kHeaderBytes, zero.data());
    for (gl::Texture& scratch : scratch_) {
        GLuint id = 0;
        glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &id);
        int levels = 1;
        while ((kFaceSize >> levels) >= 1) ++levels;
        glTextureStorage2D(id, levels, GL_RGBA32F, kFaceSize, kFaceSize);
        glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        scratch = gl::Texture(id);
    }
    environmentWeights_ = cubeArray(kFaceSize, kLevels, 6 * 4);   // 2 slices x 2 NDFs
}

EnvironmentGlints::~EnvironmentGlints() = default;

void EnvironmentGlints::buildLevels(const EnvironmentGlintSettings& settings, GLuint sourceCube, int sourceFaceSize) {
    int mip = 0;
    while ((sourceFaceSize >> mip) > kFaceSize) ++mip;
    const int size = std::max(sourceFaceSize >> mip, 1);
    const int groups = (size + 15) / 16;
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_ENV_GLINTS, block_.id());
    glBindTextureUnit(UNIT_GLINT_LEVEL_SOURCE, sourceCube);
    reduceTexels_.use();
    glUniform1i(0, size);
    glUniform1i(1, mip);
    glUniform1f(2, settings.blackLevel);
    glUniform1i(3, settings.levels);
    glDispatchCompute(GLuint(groups), GLuint(groups), 6);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    reduceGroups_.use();
    glUniform1f(2, settings.blackLevel);
    glUniform1i(3, settings.levels);
    glUniform1i(4, groups * groups * 6);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void EnvironmentGlints::buildWeights(bool probe, GLuint source, int sourceCube, float sourceMip, GLuint target,
                                     int firstLayerFace, int slices) {
    (probe ? probeWeightsProgram_ : weights_).use();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BINDING_ENV_GLINTS, block_.id());
    glBindTextureUnit(UNIT_GLINT_LEVEL_SOURCE, source);
    glBindImageTexture(0, scratch_[0].id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(1, scratch_[1].id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glUniform1i(0, kFaceSize);
    glUniform1f(1, sourceMip);
    glUniform1i(2, sourceCube);
    glDispatchCompute(GLuint((kFaceSize + 7) / 8), GLuint((kFaceSize + 7) / 8), 6);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    if (!prefilter_) prefilter_ = std::make_unique<CubePrefilter>(shaderRoot_);
    for (int slice = 0; slice < slices; ++slice) {
        glGenerateTextureMipmap(scratch_[slice].id());
        // Level 0 is the unfiltered weights (the mirror's); levels 1.. the GGX and Beckmann prefilter of the radiance.
        for (int ndf = 0; ndf < 2; ++ndf)
            glCopyImageSubData(scratch_[slice].id(), GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, target, GL_TEXTURE_CUBE_MAP_ARRAY, 0,
                               0, 0, firstLayerFace + 6 * (2 * slice + ndf), kFaceSize, kFaceSize, 6);
        prefilter_->runMipChain(scratch_[slice].id(), kFaceSize, target, kLevels, firstLayerFace + 12 * slice, 0x3u);
    }
}

std::vector<std::pair<std::string, double>> EnvironmentGlints::update(const EnvironmentGlintSettings& settings,
                                                                      GLuint sourceCube, int sourceFaceSize,
                                                                      const std::string& environmentKey,
                                                                      const Probes& probes, bool measure) {
    const int probeCount = probes.array ? probes.count : 0;
    const std::string key = environmentKey + "|levels " + std::to_string(settings.levels) + "|black " +
                            std::to_string(settings.blackLevel) + "|probes " + std::to_string(probes.captures) + "x" +
                            std::to_string(probeCount);
    if (key == key_ || settings.levels <= 0 || !sourceCube) return {};
    const auto start = std::chrono::steady_clock::now();
    if (!reduceTexels_) {   // built on first use: a renderer whose method draws no environment glints never compiles them
        const std::string levels = "environment/glint_levels.comp", weights = "environment/glint_weights.comp";
        reduceTexels_ = gl::Program(shaderRoot_, {"environment/glint_levels", {{GL_COMPUTE_SHADER, levels}}, {"REDUCE_TEXELS"}});
        reduceGroups_ = gl::Program(shaderRoot_, {"environment/glint_levels", {{GL_COMPUTE_SHADER, levels}}, {"REDUCE_GROUPS"}});
        weights_ = gl::Program(shaderRoot_, {"environment/glint_weights", {{GL_COMPUTE_SHADER, weights}}});
        probeWeightsProgram_ =
            gl::Program(shaderRoot_, {"environment/glint_weights", {{GL_COMPUTE_SHADER, weights}}, {"PROBE_SOURCE"}});
    }
    buildLevels(settings, sourceCube, sourceFaceSize);
    const int slices = settings.levels > 4 ? 2 : 1;
    buildWeights(false, sourceCube, 0, 0.0f, environmentWeights_.id(), 0, slices);
    // The probes' weights: from each probe's unfiltered capture (level 0 of its array, layer 2 x probe), read at the
    // weights' face size (a 128 probe face: bilinear at each 2 x 2 block's centre, its box mean).
    if (probeCount != probeCount_ || !probeWeights_) {
        probeWeights_ = cubeArray(kFaceSize, kLevels, 6 * 4 * std::max(probeCount, 1));
        probeCount_ = probeCount;
    }
    for (int i = 0; i < probeCount; ++i)
        buildWeights(true, probes.array, 2 * i, 0.0f, probeWeights_.id(), 24 * i, slices);
    glNamedBufferSubData(block_.id(), 48 + 8, 4, &probeCount);   // info.z
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    if (measure) glFinish();
    key_ = key;
    ++builds_;
    return {{"env_glints.levels", elapsedMs(start)}};
}

std::vector<float> EnvironmentGlints::levels() const {
    std::vector<float> header(16, 0.0f);
    glGetNamedBufferSubData(block_.id(), 0, kHeaderBytes, header.data());
    return {header.begin(), header.begin() + kMaxLevels};
}

int EnvironmentGlints::levelCount() const {
    int info[4] = {0, 0, 0, 0};
    glGetNamedBufferSubData(block_.id(), 48, 16, info);
    return info[0];
}

}  // namespace glimmer
