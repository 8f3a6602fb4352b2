#include "render/probes/reflection_probes.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>

#include "core/cache_file.h"
#include "core/clock.h"
#include "core/log.h"
#include "glints/methods.h"
#include "environment/ibl/ibl_modes.h"
#include "environment/ibl/object_environment.h"
#include "environment/environment.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"
#include "scene/scene_hash.h"

namespace glimmer {

ProbeSettings probeSettings(const RenderSettings& settings) {
    ProbeSettings p;
    p.enabled = settings.value(param::probes_enabled) > 0.5f;
    p.faceSize = int(settings.value(param::probes_face_size));
    p.maxProbes = std::clamp(int(settings.value(param::probes_max)), 0, kMaxReflectionProbes);
    return p;
}

namespace {

int mipCount(int size) {
    int levels = 1;
    while ((size >> levels) > 0) ++levels;
    return levels;
}

void setCubeSampling(GLuint texture) {
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
}

// The settings a capture renders with: the default method and IBL mode (whatever the frame uses), the frame's
// common parameters (exposure, ambient, env.intensity / rotation, lod...), and nothing that needs this camera or
// other frames: no probes (no probe sees another), no shadows (the maps are fitted to the main camera, not to a
// probe's six faces, so a capture sees direct light unshadowed: docs/reflection_probes.md), no ambient occlusion,
// no TAA and no image pipeline.
RenderSettings captureSettings(const RenderSettings& frame) {
    RenderSettings settings;
    settings.common = frame.common;
    for (const char* off : {"probes.enabled=0", "shadow.enabled=0", "ao.enabled=0", "aa=off", "lighting.split_glinty=0"})
        settings.apply(off);
    return settings;
}

// Common parameters a capture never reads: those of the passes captureSettings turns off, and those of the image
// pipeline after the HDR image a capture reads back (exposure, tone curve, bloom, anti-aliasing). A change of one of
// them re-captured all probes (seconds on a software renderer); exposure, TAA or a shadow filter changed in the
// window or between tests now reuses them.
bool captureIgnores(const std::string& name) {
    for (const char* prefix : {"exposure", "tonemap", "bloom.", "aa", "ssaa.", "taa.", "shadow.", "ao.", "probes.",
                               "lighting.split_glinty", "lighting.glint_footprint"})
        if (name.rfind(prefix, 0) == 0) return true;
    return false;
}

// Everything a capture depends on. Meshes are keyed by their sizes: a scene's meshes change only with the scene.
void buildKey(const Scene& scene, const RenderSettings& settings, const ProbeSettings& probes,
              std::vector<float>& key, std::string& text) {
    key.clear();
    key.insert(key.end(), {float(probes.enabled), float(probes.faceSize), float(probes.maxProbes)});
    for (const MeshData& mesh : scene.meshes) key.insert(key.end(), {float(mesh.positions.size()), float(mesh.indices.size())});
    for (const Instance& instance : scene.instances) {
        key.insert(key.end(), {float(instance.mesh), float(instance.material)});
        const float* m = &instance.transform[0][0];
        key.insert(key.end(), m, m + 16);
    }
    for (const Material& m : scene.materials)
        key.insert(key.end(), {m.baseColor[0], m.baseColor[1], m.baseColor[2], m.baseColor[3], m.alpha, m.metallic,
                               float(int(m.ndf)), float(m.glinty), m.shadingDensityScale(), m.alphaCutoff,
                               float(m.doubleSided), float(m.baseColorTexture), float(m.metallicRoughnessTexture),
                               float(m.normalTexture)});
    for (const Light& l : scene.lights)
        key.insert(key.end(), {float(int(l.type)), l.vector.x, l.vector.y, l.vector.z, l.color[0], l.color[1],
                               l.color[2], l.intensity, l.spotDirection.x, l.spotDirection.y, l.spotDirection.z,
                               l.right.x, l.right.y, l.right.z, l.width, l.height, l.radius, l.angularDiameter,
                               l.innerConeAngle, l.outerConeAngle, l.range, float(l.twoSided)});
    key.insert(key.end(), {scene.skyColor.x, scene.skyColor.y, scene.skyColor.z});
    const RenderSettings capture = captureSettings(settings);
    for (const CommonParam& p : commonParams())
        if (!captureIgnores(p.spec.name)) key.push_back(capture.value({p.spec.name.c_str()}));
    std::ostringstream out;
    out << scene.name << '\n' << scene.environment << '\n' << scene.textures.size();
    text = out.str();
}

}  // namespace

ReflectionProbes::ReflectionProbes(std::filesystem::path shaderRoot) : shaderRoot_(std::move(shaderRoot)) {
    probeBlock_ = gl::createBuffer(sizeof(ProbeUniforms), nullptr);
    ProbeUniforms none{};
    none.params = {0.0f, float(kLevels - 1), 0.0f, 0.0f};
    emptyBlock_ = gl::createBuffer(sizeof(ProbeUniforms), &none);
    // The empty array: a cube-map array of the probes' format, mip count and sampling (one probe's 12 layer-faces,
    // zero). llvmpipe compiles a program for the kind of texture bound to each unit, so a frame without probes that
    // bound nothing compiled the lighting program a second time (seconds) once the probes came.
    const int size = 1 << (kLevels - 1);
    GLuint array = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &array);
    emptyArray_ = gl::Texture(array);
    glTextureStorage3D(array, kLevels, GL_RGBA32F, size, size, 12);
    setCubeSampling(array);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int level = 0; level < kLevels; ++level) glClearTexImage(array, level, GL_RGBA, GL_FLOAT, zero);
}

ReflectionProbes::~ReflectionProbes() = default;

void ReflectionProbes::invalidate() {
    captured_ = false;
    shaderHash_.clear();
    renderer_.reset();
    prefilter_.reset();
}

ReflectionProbes::Update ReflectionProbes::update(const Scene& scene, const GpuScene& gpuScene,
                                                  Environment& environment, const RenderSettings& settings,
                                                  bool mayCapture) {
    ProbeSettings ps = probeSettings(settings);
    std::vector<float> key;
    std::string text;
    buildKey(scene, settings, ps, key, text);
    if (captured_ && key == key_ && text == keyText_) return {};
    const bool wanted = ps.enabled && ps.maxProbes > 0 && environment.enabled();
    // Captured against a preview environment they would be lit wrongly and keyed as if right.
    if (wanted && !environment.refined()) return {.waiting = true};
    Update timings;
    Stopwatch clock;
    const std::string disk = wanted ? diskKey(scene, environment, ps, key) : "";
    const bool loaded = !disk.empty() && loadFromDisk(disk, scene, ps.faceSize);
    if (wanted && !loaded && !mayCapture) return {.waiting = true};
    key_ = std::move(key);
    keyText_ = std::move(text);
    captured_ = true;
    if (!loaded) probes_.clear();
    if (!wanted) return timings;
    if (loaded) {
        timings.ran = timings.fromDisk = true;
        timings.loadMs = clock.elapsedMs();
        last_ = timings;
        ++diskLoads_;
        log::info("reflection probes: ", probes_.size(), " read from the cache in ", timings.loadMs, " ms");
        return timings;
    }
    capture(scene, gpuScene, environment, settings, ps, timings);
    timings.ran = true;
    last_ = timings;
    ++captures_;
    log::info("reflection probes: ", probes_.size(), " captured at ", ps.faceSize, "^2, capture ", timings.captureMs,
              " ms, prefilter ", timings.prefilterMs, " ms");
    if (!disk.empty() && !probes_.empty()) storeToDisk(disk);
    return timings;
}

void ReflectionProbes::capture(const Scene& scene, const GpuScene& gpuScene, Environment& environment,
                               const RenderSettings& settings, const ProbeSettings& ps, Update& timings) {
    std::vector<ProbePlacement> placements = placeReflectionProbes(scene, ps.maxProbes);
    if (placements.empty()) return;
    Stopwatch clock;
    const RenderSettings renderSettings = captureSettings(settings);
    if (!renderer_) {
        renderer_ = std::make_unique<Renderer>(shaderRoot_, renderSettings, FrameKind::Capture, &environment);
        prefilter_ = std::make_unique<CubePrefilter>(shaderRoot_);
    }
    renderer_->setSettings(renderSettings);
    const int size = ps.faceSize;
    if (!source_ || faceSize_ != size) {
        GLuint cube = 0;
        glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &cube);
        source_ = gl::Texture(cube);
        glTextureStorage2D(cube, mipCount(size), GL_RGBA32F, size, size);
        setCubeSampling(cube);
    }
    faceSize_ = size;
    const Box limits = sceneBounds(scene);
    const size_t texels = size_t(size) * size;
    std::vector<std::vector<float>> faces[kMaxReflectionProbes];
    std::vector<Probe> captured;
    std::vector<float> hdr(texels * 4), depth(texels);
    for (const ProbePlacement& placement : placements) {
        // The scene without the probe's own object: GpuScene draws instances by mesh index, materials by index,
        // so a copy of the instance list and materials is all a draw needs (no mesh copy).
        Scene view;
        view.materials = scene.materials;
        view.skyColor = scene.skyColor;
        view.environment = scene.environment;
        for (size_t i = 0; i < scene.instances.size(); ++i)
            if (int(i) != placement.excludedInstance) view.instances.push_back(scene.instances[i]);
        std::array<std::vector<float>, 6> axisDistance;
        std::vector<std::vector<float>> rgba(6);
        size_t covered = 0;
        for (int face = 0; face < 6; ++face) {
            View faceView{.camera = ibl::cubeFaceCamera(placement.position, face), .width = size, .height = size};
            renderer_->renderView(view, gpuScene, faceView);
            const Camera& camera = faceView.camera;
            hdr = renderer_->readHdr();
            depth = renderer_->readDepth();
            // Sky texels become (0, 0, 0, 0): premultiplied radiance and coverage. Reversed-Z infinite projection:
            // view distance along the face axis = near / depth.
            axisDistance[size_t(face)].resize(texels);
            for (size_t t = 0; t < texels; ++t) {
                bool sky = depth[t] <= 0.0f;
                axisDistance[size_t(face)][t] = sky ? INFINITY : camera.nearPlane / depth[t];
                if (sky) {
                    for (int c = 0; c < 4; ++c) hdr[t * 4 + c] = 0.0f;
                } else {
                    hdr[t * 4 + 3] = 1.0f;
                    ++covered;
                }
            }
            rgba[size_t(face)] = hdr;
        }
        if (covered == 0) continue;   // sees only sky: the distant environment is exact there
        Probe probe;
        probe.placement = placement;
        probe.coverage = float(double(covered) / double(6 * texels));
        probe.proxy = fitProxyBox(placement.position, axisDistance, limits,
                                  {glm::min(placement.influence.min, placement.position),
                                   glm::max(placement.influence.max, placement.position)});
        faces[captured.size()] = std::move(rgba);
        captured.push_back(probe);
    }
    glFinish();
    timings.captureMs = clock.elapsedMs();
    clock.restart();

    probes_ = std::move(captured);
    if (probes_.empty()) {
        specular_.reset();
        return;
    }
    allocateArray(size, probes_.size());
    const GLuint array = specular_.id();
    // Only the NDFs some material uses are prefiltered (the key holds the materials: a change re-captures).
    unsigned ndfMask = 0;
    for (const Material& m : scene.materials) ndfMask |= 1u << std::clamp(int(m.ndf), 0, 1);
    for (size_t p = 0; p < probes_.size(); ++p) {
        for (int face = 0; face < 6; ++face)
            glTextureSubImage3D(source_.id(), 0, 0, 0, face, size, size, 1, GL_RGBA, GL_FLOAT, faces[p][size_t(face)].data());
        glGenerateTextureMipmap(source_.id());
        for (int ndf = 0; ndf < 2; ++ndf)
            glCopyImageSubData(source_.id(), GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, array, GL_TEXTURE_CUBE_MAP_ARRAY, 0, 0, 0,
                               GLint(12 * p + 6 * ndf), size, size, 6);
        prefilter_->runMipChain(source_.id(), size, array, kLevels, int(12 * p), ndfMask);
    }
    glFinish();
    timings.prefilterMs = clock.elapsedMs();
    uploadProbeBlock();
}

void ReflectionProbes::allocateArray(int size, size_t count) {
    GLuint array = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &array);
    specular_ = gl::Texture(array);
    glTextureStorage3D(array, kLevels, GL_RGBA32F, size, size, GLsizei(6 * 2 * count));
    setCubeSampling(array);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int level = 0; level < kLevels; ++level) glClearTexImage(array, level, GL_RGBA, GL_FLOAT, zero);
}

void ReflectionProbes::uploadProbeBlock() {
    ProbeUniforms u{};
    u.params = {float(probes_.size()), float(kLevels - 1), 0.0f, 0.0f};
    for (size_t p = 0; p < probes_.size(); ++p) {
        const Probe& probe = probes_[p];
        u.probes[p].position = glm::vec4(probe.placement.position, probe.placement.fade);
        u.probes[p].influenceMin = glm::vec4(probe.placement.influence.min, 0.0f);
        u.probes[p].influenceMax = glm::vec4(probe.placement.influence.max, 0.0f);
        u.probes[p].proxyMin = glm::vec4(probe.proxy.min, 0.0f);
        u.probes[p].proxyMax = glm::vec4(probe.proxy.max, 0.0f);
    }
    glNamedBufferSubData(probeBlock_.id(), 0, sizeof(u), &u);
}

bool ReflectionProbes::diskCacheEnabled() {
    const char* v = std::getenv("GLIMMER_PROBE_CACHE");
    return !(v && std::string(v) == "0");
}

namespace {
constexpr uint32_t kProbeCacheLayout = 1;   // bump when the payload below or the capture changes
constexpr size_t kRecordFloats = 18;        // per probe: position, fade, influence min / max, excluded, proxy, coverage

// Every file under the shader root, by relative path and bytes.
std::string shaderFolderHash(const std::filesystem::path& root) {
    std::vector<std::filesystem::path> files;
    std::error_code ec;
    for (auto it = std::filesystem::recursive_directory_iterator(root, ec); !ec && it != std::filesystem::end(it);
         it.increment(ec))
        if (it->is_regular_file(ec)) files.push_back(it->path());
    std::sort(files.begin(), files.end());
    cache::ContentHasher hash;
    for (const auto& file : files) {
        hash.add(std::filesystem::relative(file, root, ec).generic_string());
        hash.add(cache::fileContentHash(file));
    }
    return hash.digest();
}

size_t arrayFloats(int faceSize, size_t count) {
    size_t floats = 0;
    for (int level = 0; level < ReflectionProbes::kLevels; ++level) {
        size_t side = size_t(std::max(faceSize >> level, 1));
        floats += side * side * 6 * 2 * count * 4;
    }
    return floats;
}
}  // namespace

std::string ReflectionProbes::diskKey(const Scene& scene, const Environment& environment, const ProbeSettings& ps,
                                      const std::vector<float>& settingsKey) {
    if (!diskCacheEnabled() || environment.contentKey().empty()) return "";
    if (shaderHash_.empty()) shaderHash_ = shaderFolderHash(shaderRoot_);
    std::ostringstream key;
    key.precision(9);
    key << "face " << ps.faceSize << " max " << ps.maxProbes << " levels " << kLevels << " | settings";
    // The in-memory key (probe settings, meshes, instances, materials, lights, sky, every common parameter, what
    // update() compares between frames), hashed: its text would grow with the instance count.
    key << ' ' << cache::contentHash({reinterpret_cast<const char*>(settingsKey.data()), settingsKey.size() * sizeof(float)});
    key << " | scene " << sceneContentHash(scene) << " | environment " << cache::contentHash(environment.contentKey())
        << " | shaders " << shaderHash_;
    return key.str();
}

bool ReflectionProbes::loadFromDisk(const std::string& key, const Scene& scene, int faceSize) {
    cache::CacheDir dir(cache::defaultCacheDir());
    const cache::CacheKey cacheKey{"reflection-probes", kProbeCacheLayout, key};
    const std::string name = "probes_" + cache::contentHash(key) + ".bin";
    auto countOf = [](std::string_view payload) {
        float count = 0.0f;
        if (payload.size() >= sizeof count) std::memcpy(&count, payload.data(), sizeof count);
        return count;
    };
    auto validate = [&](std::string_view payload) {
        const float count = countOf(payload);
        if (!(count >= 1.0f && count <= float(kMaxReflectionProbes)) || count != std::floor(count)) return false;
        const size_t probes = size_t(count);
        if (payload.size() != (1 + probes * kRecordFloats + arrayFloats(faceSize, probes)) * sizeof(float)) return false;
        const size_t floats = payload.size() / sizeof(float);
        for (size_t i = 0; i < floats; ++i) {
            float v;
            std::memcpy(&v, payload.data() + i * sizeof v, sizeof v);
            if (!std::isfinite(v)) return false;
            const size_t texel = i - (1 + probes * kRecordFloats);
            // Radiance >= 0; coverage (alpha) <= 1 up to the prefilter's overshoot (at most 1.019 measured).
            if (i > probes * kRecordFloats && (v < 0.0f || (texel % 4 == 3 && v > 1.1f))) return false;
        }
        for (size_t p = 0; p < probes; ++p) {
            float excluded, coverage;
            std::memcpy(&excluded, payload.data() + (1 + p * kRecordFloats + 10) * sizeof(float), sizeof excluded);
            std::memcpy(&coverage, payload.data() + (1 + p * kRecordFloats + 17) * sizeof(float), sizeof coverage);
            if (excluded < -1.0f || excluded >= float(scene.instances.size()) || !(coverage > 0.0f && coverage <= 1.0f))
                return false;
        }
        return true;
    };
    std::optional<std::string> payload = dir.load(name, cacheKey, 0, validate);
    if (!payload) return false;
    const size_t count = size_t(countOf(*payload));
    const float* values = reinterpret_cast<const float*>(payload->data()) + 1;
    std::vector<Probe> loaded(count);
    for (size_t p = 0; p < count; ++p, values += kRecordFloats) {
        const float* r = values;
        Probe& probe = loaded[p];
        probe.placement.position = {r[0], r[1], r[2]};
        probe.placement.fade = r[3];
        probe.placement.influence = {{r[4], r[5], r[6]}, {r[7], r[8], r[9]}};
        probe.placement.excludedInstance = int(r[10]);
        probe.proxy = {{r[11], r[12], r[13]}, {r[14], r[15], r[16]}};
        probe.coverage = r[17];
    }
    probes_ = std::move(loaded);
    faceSize_ = faceSize;
    allocateArray(faceSize, count);
    for (int level = 0; level < kLevels; ++level) {
        const int side = std::max(faceSize >> level, 1);
        glTextureSubImage3D(specular_.id(), level, 0, 0, 0, side, side, GLsizei(6 * 2 * count), GL_RGBA, GL_FLOAT,
                            values);
        values += size_t(side) * size_t(side) * 6 * 2 * count * 4;
    }
    uploadProbeBlock();
    return true;
}

void ReflectionProbes::storeToDisk(const std::string& key) const {
    const size_t count = probes_.size();
    std::vector<float> payload;
    payload.reserve(1 + count * kRecordFloats + arrayFloats(faceSize_, count));
    payload.push_back(float(count));
    for (const Probe& probe : probes_) {
        const ProbePlacement& p = probe.placement;
        payload.insert(payload.end(), {p.position.x, p.position.y, p.position.z, p.fade, p.influence.min.x,
                                       p.influence.min.y, p.influence.min.z, p.influence.max.x, p.influence.max.y,
                                       p.influence.max.z, float(p.excludedInstance), probe.proxy.min.x,
                                       probe.proxy.min.y, probe.proxy.min.z, probe.proxy.max.x, probe.proxy.max.y,
                                       probe.proxy.max.z, probe.coverage});
    }
    for (int level = 0; level < kLevels; ++level) {
        const int side = std::max(faceSize_ >> level, 1);
        const size_t at = payload.size(), floats = size_t(side) * size_t(side) * 6 * 2 * count * 4;
        payload.resize(at + floats);
        glGetTextureImage(specular_.id(), level, GL_RGBA, GL_FLOAT, GLsizei(floats * sizeof(float)), payload.data() + at);
    }
    cache::CacheDir dir(cache::defaultCacheDir());
    const std::string name = "probes_" + cache::contentHash(key) + ".bin";
    if (dir.store(name, {"reflection-probes", kProbeCacheLayout, key},
                  {reinterpret_cast<const char*>(payload.data()), payload.size() * sizeof(float)}))
        dir.pruneLeastRecentlyUsed("probes_", ".bin", cache::keptFilesPerKind(kMaxCacheFiles));
}

FrameImage ReflectionProbes::image(bool active) const {
    const bool any = active && !probes_.empty() && specular_;
    if (!any) return {.textures = {emptyArray_.id()}, .buffer = emptyBlock_.id(), .width = 0, .height = 0};
    return {.textures = {specular_.id()}, .buffer = probeBlock_.id(), .width = faceSize_, .height = faceSize_};
}

void bindProbeInputs(const FrameImage& probes) {
    glBindBufferBase(GL_UNIFORM_BUFFER, kProbeBinding, probes.buffer);
    glBindTextureUnit(kProbeSpecularUnit, probes.texture());
}

nlohmann::json ReflectionProbes::stats() const {
    nlohmann::json probes = nlohmann::json::array();
    for (const Probe& p : probes_) {
        auto v = [](glm::vec3 x) { return nlohmann::json::array({x.x, x.y, x.z}); };
        probes.push_back({{"position", v(p.placement.position)},
                          {"instance", p.placement.excludedInstance},
                          {"influence", {v(p.placement.influence.min), v(p.placement.influence.max)}},
                          {"proxy", {v(p.proxy.min), v(p.proxy.max)}},
                          {"coverage", p.coverage}});
    }
    return {{"count", probes_.size()},
            {"face_size", faceSize_},
            {"captures", captures_},
            {"last_capture_ms", last_.captureMs},
            {"last_prefilter_ms", last_.prefilterMs},
            {"probes", probes}};
}

}  // namespace glimmer
