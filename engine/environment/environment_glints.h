// Environment glints (Kneiphof & Klein 2025, "Real-time Image-based Lighting of Glints", EGSR 2025, Sec. 4.1): the
// data the lighting pass needs to draw glints from the environment (shaders/environment/glint_levels.glsl):
// - the radiance levels: the distant environment's luminance range above a black level, found by two reduction
//   dispatches (shaders/environment/glint_levels.comp), split into K = 4 or 8 log-spaced levels (level 0 = 0);
// - per level, the indicator weights of every texel (its luminance shared linearly between the two levels around
//   it; shaders/environment/glint_weights.comp), prefiltered by the GGX / Beckmann convolution of the radiance
//   (environment/cube_prefilter.h) into a mip chain whose level k holds sqrt(alpha) = k / 5, for the distant
//   environment and, which the paper leaves out, for every reflection probe (premultiplied by its coverage, as the
//   lighting pass blends probe and sky).
// Built when the environment, the probes or the settings change, never on a still frame (the paper runs it every
// frame for dynamic skies; here the maps are rebuilt exactly when they change). About twice the memory of the
// radiance at this face size (the paper's estimate).
#pragma once
#include <glad/gl.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "environment/cube_prefilter.h"

namespace glimmer {

struct IblMode;

struct EnvironmentGlintSettings {
    int levels = 4;             // K: 4 or 8 (0: off)
    float blackLevel = 1e-2f;   // luminance below which a texel is dark (the paper's default)
    bool operator==(const EnvironmentGlintSettings&) const = default;
};

// From the IBL mode's parameters glint_levels (off, 4, 8) and glint_black_level; levels 0 for a mode without them.
EnvironmentGlintSettings environmentGlintSettings(const IblMode& mode, const std::map<std::string, float>& values);

class EnvironmentGlints {
public:
    static constexpr int kFaceSize = 64;    // of the weights (the environment's mip 2; a probe's 128 halved)
    static constexpr int kLevels = 6;       // mip chain: level k holds sqrt(alpha) = k / 5
    static constexpr int kMaxLevels = 8;

    // Creates the buffers and textures; the programs are built on the first update().
    explicit EnvironmentGlints(std::filesystem::path shaderRoot);
    ~EnvironmentGlints();

    // The reflection probes as the weights read them: their cube-map array (layer 2 x probe holds a probe's
    // unfiltered capture in level 0, premultiplied, coverage in alpha), how many, and a value that changes with
    // every capture (render/probes/reflection_probes.h).
    struct Probes {
        GLuint array = 0;
        int count = 0;
        int captures = 0;
    };
    // Rebuilds the levels and the weights when the environment (`environmentKey`, its source cube with a full mip
    // chain of `sourceFaceSize` faces), the probes or the settings changed since the last build. Returns the passes
    // that ran (name, wall ms), closed by glFinish when `measure`.
    std::vector<std::pair<std::string, double>> update(const EnvironmentGlintSettings& settings, GLuint sourceCube,
                                                       int sourceFaceSize, const std::string& environmentKey,
                                                       const Probes& probes, bool measure);
    // What the lighting pass binds (render/frame/environment_glints_pass.h): the level block (BINDING_ENV_GLINTS) and
    // the environment's and the probes' weights (cube-map arrays; layer = slice x 2 + NDF, probes (probe x 2 + slice)
    // x 2 + NDF); all 0 before the first build.
    bool built() const { return !key_.empty(); }
    GLuint levelBlock() const { return built() ? block_.id() : 0; }

    // The levels' radiance and count (read back, for tests and stats).
    std::vector<float> levels() const;
    int levelCount() const;
    GLuint environmentWeights() const { return environmentWeights_.id(); }
    GLuint probeWeights() const { return probeWeights_.id(); }
    int builds() const { return builds_; }

private:
    void buildLevels(const EnvironmentGlintSettings& settings, GLuint sourceCube, int sourceFaceSize);
    // Weights of one source into `target` at layer-faces (slice 2 + ndf) 6 + firstLayerFace.
    void buildWeights(bool probe, GLuint source, int sourceCube, float sourceMip, GLuint target, int firstLayerFace,
                      int slices);

    std::filesystem::path shaderRoot_;
    gl::Program reduceTexels_, reduceGroups_, weights_, probeWeightsProgram_;
    std::unique_ptr<CubePrefilter> prefilter_;
    gl::Buffer block_;
    gl::Texture scratch_[2];                        // level-0 weights with a box mip chain (the prefilter's source)
    gl::Texture environmentWeights_, probeWeights_;
    std::string key_;
    int probeCount_ = 0;
    int builds_ = 0;
};

}  // namespace glimmer
