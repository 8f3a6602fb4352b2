// Image-based lighting from an environment: loading (equirectangular .hdr / .exr, a procedural sky with a sun, or
// a constant), conversion to a cubemap with a full mip chain, GGX and Beckmann prefiltered specular mips, diffuse
// irradiance as order-2 spherical harmonics, and the split-sum BRDF table. All maps are built on the GPU by the
// compute passes in shaders/env/; shaders/environment/prefiltered_lookup.glsl reads them in the lighting pass.
//
// Methods: split-sum approximation and prefiltered mips per roughness (Karis 2013, "Real Shading in Unreal Engine
// 4", Eq. 2-4), filtered importance sampling of the source mips (Krivanek & Colbert 2008, GPU Gems 3 ch. 20,
// Eq. 20-1/20-2), irradiance environment maps by spherical harmonics (Ramamoorthi & Hanrahan 2001, Eq. 7-8).
#pragma once
#include "common/bindings.glsl"
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "gl/handles.h"
#include "gl/program.h"
#include "environment/cube_prefilter.h"
#include "scene/scene.h"

namespace glimmer {

class EnvironmentCache;

// What `--env` / Scene::environment name: "" or "procedural" (default sky), "none", "constant:R,G,B" (or
// "constant:V"), or an image path.
struct EnvironmentSpec {
    enum class Kind { Procedural, None, Constant, File };
    Kind kind = Kind::Procedural;
    glm::vec3 constant{0.0f};
    std::filesystem::path path;
};
// Throws UsageError naming `flag` for a malformed constant; does not touch the file system.
EnvironmentSpec parseEnvironmentSpec(const std::string& text, const std::string& flag);

// The sun of the procedural sky follows the scene's first directional light. When that light exists it already
// lights the scene analytically, so the sun disk is drawn in the background (and mirror level) only and kept out
// of the prefiltered and irradiance maps (no double counting); without one, the sun is part of the lighting.
struct SunDescription {
    bool analytic = false;               // a directional light carries the sun's direct light
    glm::vec3 direction{0.3f, 0.55f, -0.78f};
    glm::vec3 irradiance{3.0f};          // colour x intensity: irradiance at normal incidence
    bool operator==(const SunDescription&) const = default;
};
SunDescription sunFromScene(const Scene& scene);

// Wall-clock milliseconds of each precompute step (each closed by glFinish).
struct EnvironmentTimings {
    double loadMs = 0, convertMs = 0, mipsMs = 0, prefilterMs = 0, irradianceMs = 0, brdfLutMs = 0, totalMs = 0;
    bool cacheHit = false;      // read from the disk cache (environment/environment_cache.h): loadMs is that read
    bool cacheStored = false;   // built and written to the disk cache
    double cacheStoreMs = 0;
};

// The uniform block of shaders/environment/prefiltered_lookup.glsl (std140, binding kEnvironmentBinding).
struct EnvironmentUniforms {
    glm::vec4 sh[9];        // rgb: irradiance / pi as order-2 SH coefficients (already cosine-convolved)
    glm::vec4 params;       // x intensity, y enabled (0/1), z kRungs - 1, w kRungAlphaMin
    glm::vec4 rotation;     // x cos, y sin of env.rotation (about +y)
};
static_assert(sizeof(EnvironmentUniforms) == 11 * 16);

constexpr unsigned kEnvironmentBinding = BINDING_ENVIRONMENT;      // uniform block binding
constexpr unsigned kEnvironmentSpecularUnit = UNIT_ENV_SPECULAR;   // samplerCubeArray: rung 0 (unfiltered), layer = NDF
constexpr unsigned kEnvironmentBrdfLutUnit = UNIT_ENV_BRDF_LUT;    // sampler2D: rg GGX (A, B), ba Beckmann (A, B)
constexpr unsigned kEnvironmentSourceUnit = UNIT_ENV_SOURCE;       // samplerCube: unfiltered map with box mips (IBL modes)
constexpr unsigned kEnvironmentSpecularFineUnit = UNIT_ENV_SPECULAR_FINE;   // samplerCubeArray: the sublevels

class Environment {
public:
    static constexpr int kFaceSize = 256;        // source cube face (level 0 of every map)
    // The specular lookup's roughness ladder: rung 0 is the unfiltered map (mirror reflections, the background),
    // rungs 1 .. kRungs hold alpha = kRungAlphaMin x (1 / kRungAlphaMin)^((rung - 1) / (kRungs - 1)): 0.04 .. 1,
    // each 1.24x the last, in a cube-map array of half the face size (specularFineArray), kSublevels rungs per
    // mip: rung i at mip (i - 1) / kSublevels, cube ndf x kSublevels + (i - 1) % kSublevels. Finer than a mip chain
    // (whose levels are 4x apart in alpha at the low end) so that a lookup between two rungs follows a small lamp
    // (docs/environment.md, "Roughness ladder"); the roughest rungs keep 16 x 16 faces, not 8 x 8.
    static constexpr int kRungs = 16;
    static constexpr int kSublevels = 4;
    static constexpr int kFineLevels = kRungs / kSublevels;   // 128 .. 16
    static constexpr float kRungAlphaMin = 0.04f;
    static float rungAlpha(int rung) {
        return kRungAlphaMin * std::pow(1.0f / kRungAlphaMin, float(rung - 1) / float(kRungs - 1));
    }
    static int rungMip(int rung) { return (rung - 1) / kSublevels; }
    static int rungCube(int rung, int ndf) { return ndf * kSublevels + (rung - 1) % kSublevels; }
    static constexpr int kBrdfLutSize = 64;
    static constexpr int kIrradianceFace = 32;   // source mip projected onto SH

    explicit Environment(std::filesystem::path shaderRoot);

    // Makes `spec` the active environment; rebuilds only when the spec (or, for the procedural sky, the sun)
    // changed. `flag` names where the spec came from in error messages ("--env" or "scene environment").
    // Throws Error naming the flag and file when an image cannot be read or holds no RGB data.
    // With `preview`, maps missing from the disk cache come in two steps: now everything but the specular prefilter
    // (the rungs are filled from the source's box mips, a few ms instead of 1-3 s on llvmpipe), and refine() later
    // (the window's first picture; Renderer::RefinementPace). Without, update() refines at once.
    void update(const std::string& spec, const SunDescription& sun, const std::string& flag, bool preview = false);
    // The maps are the prefiltered ones (false only between a preview update() and refine()). Data derived from
    // the specular maps and cached on disk (the reflection probes) waits for it.
    bool refined() const { return refined_; }
    // Prefilters the specular rungs and stores the maps in the disk cache; nothing when already refined.
    void refine();
    // refine() in steps of one prefilter walk (CubePrefilter::step: 0.2-1 s each on llvmpipe, where the whole is
    // 1.2-3 s), for a window that spreads it over frames; true once refined. The rungs not yet walked keep the
    // preview.
    bool refineStep();
    // Walks done and their count while refining ({0, 1} before the first step, {1, 1} when refined).
    std::pair<int, int> refineProgress() const;
    bool enabled() const { return enabled_; }
    // What the active maps were built from, as the disk cache keys them (the image's bytes or the procedural sky's
    // sun, the map sizes, the shaders' sources): "" for none or with the cache off (GLIMMER_ENV_CACHE=0). Caches of
    // data that see the environment (the reflection probes) key on it.
    const std::string& contentKey() const { return contentKey_; }
    // Uploads the uniform block and binds the textures (units 6-7, block binding 7) for the lighting pass.
    void bind(float intensity, float rotationDegrees);

    const EnvironmentTimings& timings() const { return timings_; }
    nlohmann::json stats() const;

    // For tests: the GPU-side maps and the SH coefficients.
    GLuint sourceCube() const { return sourceCube_.id(); }
    GLuint specularCubeArray() const { return specular_.id(); }
    // Rungs 1 .. kRungs (see kRungs).
    GLuint specularFineArray() const { return specularFine_.id(); }
    GLuint brdfLut() const { return brdfLut_.id(); }
    const std::array<glm::vec3, 9>& irradianceSh() const { return sh_; }
    // Identifies the active maps: changes whenever they are rebuilt (data derived from them key on it).
    const std::string& key() const { return activeKey_; }

private:
    // The disk cache key's parameters for `spec` ("" = do not cache: turned off, `none`, unreadable file).
    std::string cacheParameters(const EnvironmentSpec& spec, const SunDescription& sun) const;
    bool loadFromCache(const EnvironmentCache& cache);
    void buildBrdfLut();
    void buildMaps(const EnvironmentSpec& spec, const SunDescription& sun);
    void fillProceduralSky(const SunDescription& sun, bool drawSun);
    std::vector<CubePrefilter::Level> prefilterLevels() const;   // every rung, for CubePrefilter::begin
    void fillPreview();
    void projectIrradiance();

    std::filesystem::path shaderRoot_;
    gl::Program equirectProgram_, skyProgram_, lutProgram_;
    std::unique_ptr<CubePrefilter> prefilter_;   // shared with the reflection probes
    gl::Texture sourceCube_, specular_, specularFine_, brdfLut_;
    gl::Buffer uniforms_;
    std::array<glm::vec3, 9> sh_{};
    std::string activeKey_, contentKey_;
    EnvironmentSpec active_;
    bool enabled_ = false;
    bool refined_ = true;
    std::string refineCacheParameters_;   // the disk cache key refine() stores under ("": not cached)
    std::optional<CubePrefilter::Job> prefilterJob_;   // refineStep()'s walks in progress
    EnvironmentTimings timings_;
};

}  // namespace glimmer
