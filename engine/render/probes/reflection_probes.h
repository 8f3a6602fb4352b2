// Reflection probes: cube maps rendered from the scene at chosen points (render/probes/reflection_probe_placement.h),
// prefiltered like the distant environment (the same CubePrefilter, levels and NDF layers), read by the lighting
// pass through environment/prefiltered_lookup.glsl with the reflected ray parallax-corrected to each probe's proxy box (Lagarde &
// Zanuttini 2012) and blended with the distant environment by the probe's coverage: a probe stores premultiplied
// radiance with alpha 1 where it saw geometry and 0 where it saw sky, so
//     L = probe.rgb + (1 - probe.a) * L_environment
// at every prefiltered level (the prefilter filters all four channels alike).
//
// Captured only when something a probe sees changed (instances, materials, lights, environment, the common
// parameters, probes.*); a frame with nothing changed reads the cached maps. A capture renders each probe's six
// faces as views of a renderer of its own (Renderer::renderView with FrameKind::Capture: the G-buffer and lighting
// passes, the default method and IBL mode, probes off: no probe sees another probe), culled per face by GpuScene's
// chunks, then reads back colour and depth to zero the sky, fit the proxy box and upload the cube.
//
// Disk cache (core/cache_file.h): a capture is the same on every launch of the same scene, so the prefiltered array
// and the probes' placements are stored under a key of everything they depend on: the scene's content
// (scene/scene_hash.h), the environment's content key (Environment::contentKey), the probe settings and every
// common parameter, and the bytes of every file under the shader root (any shader edit recaptures: simpler than
// listing the capture renderer's and the prefilter's files, and as safe). Loaded only when the size matches the
// stored probe count and every value is finite, the radiance non-negative and the coverage in [0, 1.1] (the prefilter overshoots 1 by up to 2%); written
// atomically; the folder keeps the kMaxCacheFiles most recently used probe files. GLIMMER_PROBE_CACHE=0 turns it
// off (timing the capture itself), and so does an environment without a content key.
#pragma once
#include "common/bindings.glsl"
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "environment/cube_prefilter.h"
#include "gl/handles.h"
#include "render/frame/frame_resources.h"
#include "render/probes/reflection_probe_placement.h"
#include "render/settings.h"

namespace glimmer {

class Environment;
class GpuScene;
class Renderer;

// std140 mirror of ProbeBlock in shaders/environment/prefiltered_lookup.glsl.
struct GpuProbe {
    glm::vec4 position;       // xyz capture point, w fade distance
    glm::vec4 influenceMin;   // xyz (w unused)
    glm::vec4 influenceMax;
    glm::vec4 proxyMin;
    glm::vec4 proxyMax;
};
constexpr int kMaxReflectionProbes = 8;
struct ProbeUniforms {
    glm::vec4 params;         // x probe count, y last prefiltered level
    GpuProbe probes[kMaxReflectionProbes];
};
static_assert(sizeof(ProbeUniforms) == 16 + kMaxReflectionProbes * 80);

constexpr unsigned kProbeBinding = BINDING_PROBES;
constexpr unsigned kProbeSpecularUnit = UNIT_PROBE_SPECULAR;

// The probes' parameters (common parameters, `--set probes.enabled=0`).
struct ProbeSettings {
    bool enabled = true;
    int faceSize = 128;
    int maxProbes = kMaxReflectionProbes;
};
ProbeSettings probeSettings(const RenderSettings& settings);

// Binds a FrameResource::ReflectionProbes image (block and array) for the lighting pass.
void bindProbeInputs(const FrameImage& probes);

class ReflectionProbes {
public:
    static constexpr int kLevels = 6;   // as the environment: level k holds sqrt(alpha) = k / 5

    explicit ReflectionProbes(std::filesystem::path shaderRoot);
    ~ReflectionProbes();

    struct Update {
        bool ran = false;                            // the probes changed (captured, or read from the disk cache)
        bool fromDisk = false;                       // read from the disk cache: loadMs, no capture
        double captureMs = 0.0, prefilterMs = 0.0;   // wall clock around glFinish
        double loadMs = 0.0;
        // Not updated this frame: the environment is still a preview (Environment::refined), or a capture was
        // needed and `mayCapture` was false. The old probes stand until then; image() should not be published.
        bool waiting = false;
    };
    static constexpr size_t kMaxCacheFiles = 4;
    static bool diskCacheEnabled();   // GLIMMER_PROBE_CACHE != 0
    // Re-captures and prefilters the probes when anything they see changed since the last capture. The
    // environment must be prepared for `scene`. Leaves the frame uniform blocks bound to its own buffers.
    // With `mayCapture` false only the disk cache may supply them (Renderer::RefinementPace).
    Update update(const Scene& scene, const GpuScene& gpuScene, Environment& environment,
                  const RenderSettings& settings, bool mayCapture = true);
    // The next update() captures (or reads the disk cache) again, with a new capture renderer and shader digest:
    // what a fresh ReflectionProbes would do. Called when the renderer rebuilt its programs.
    void invalidate();
    // FrameResource::ReflectionProbes: the probe array and block, width and height the face size; `active` false (or
    // no probes) gives a block with no probes (the lighting reads the distant environment alone), a zero array of
    // the same kind and width 0.
    FrameImage image(bool active) const;

    struct Probe {
        ProbePlacement placement;
        Box proxy;
        float coverage = 0.0f;   // fraction of its texels that saw geometry
    };
    const std::vector<Probe>& probes() const { return probes_; }   // the captured ones (coverage > 0)
    int captures() const { return captures_; }                       // how many times update() captured
    int diskLoads() const { return diskLoads_; }                     // ... and read the disk cache instead
    GLuint specularArray() const { return specular_.id(); }
    int faceSize() const { return faceSize_; }
    nlohmann::json stats() const;

private:
    void capture(const Scene& scene, const GpuScene& gpuScene, Environment& environment,
                 const RenderSettings& settings, const ProbeSettings& probeSettings, Update& timings);
    // The disk cache's key parameters ("" = not cached) and its load / store.
    // `settingsKey`: buildKey's in-memory key of the probes being looked up.
    std::string diskKey(const Scene& scene, const Environment& environment, const ProbeSettings& probeSettings,
                        const std::vector<float>& settingsKey);
    bool loadFromDisk(const std::string& key, const Scene& scene, int faceSize);
    void storeToDisk(const std::string& key) const;
    // Allocates the prefiltered array for `count` probes of `size` and clears it (levels of an unused NDF stay 0).
    void allocateArray(int size, size_t count);
    void uploadProbeBlock();

    std::filesystem::path shaderRoot_;
    std::unique_ptr<Renderer> renderer_;   // renders the captures (built on the first one)
    std::unique_ptr<CubePrefilter> prefilter_;
    gl::Buffer probeBlock_, emptyBlock_;
    gl::Texture emptyArray_;   // bound while there are no probes (see the constructor)
    gl::Texture specular_, source_;
    int faceSize_ = 0;
    std::vector<Probe> probes_;
    std::vector<float> key_;
    std::string keyText_;
    bool captured_ = false;
    int captures_ = 0, diskLoads_ = 0;
    std::string shaderHash_;   // of every file under shaderRoot_ (computed on the first disk-cache key)
    Update last_;
};

}  // namespace glimmer
