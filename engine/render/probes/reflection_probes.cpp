#include "render/probes/reflection_probes.h"

#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <sstream>

#include "core/clock.h"
#include "core/log.h"
#include "glints/methods.h"
#include "environment/ibl/ibl_modes.h"
#include "environment/ibl/object_environment.h"
#include "environment/environment.h"
#include "render/gpu_scene.h"
#include "render/renderer.h"

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
                               float(int(m.ndf)), float(m.glinty), m.glintDensityScale, m.alphaCutoff,
                               float(m.doubleSided), float(m.baseColorTexture), float(m.metallicRoughnessTexture),
                               float(m.normalTexture)});
    for (const Light& l : scene.lights)
        key.insert(key.end(), {float(int(l.type)), l.vector.x, l.vector.y, l.vector.z, l.color[0], l.color[1],
                               l.color[2], l.intensity});
    key.insert(key.end(), {scene.skyColor.x, scene.skyColor.y, scene.skyColor.z});
    for (const CommonParam& p : commonParams()) key.push_back(settings.value({p.spec.name.c_str()}));
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
}

ReflectionProbes::~ReflectionProbes() = default;

ReflectionProbes::Update ReflectionProbes::update(const Scene& scene, const GpuScene& gpuScene,
                                                  Environment& environment, const RenderSettings& settings) {
    ProbeSettings ps = probeSettings(settings);
    std::vector<float> key;
    std::string text;
    buildKey(scene, settings, ps, key, text);
    if (captured_ && key == key_ && text == keyText_) return {};
    key_ = std::move(key);
    keyText_ = std::move(text);
    captured_ = true;
    Update timings;
    probes_.clear();
    if (!ps.enabled || ps.maxProbes == 0 || !environment.enabled()) return timings;
    capture(scene, gpuScene, environment, settings, ps, timings);
    timings.ran = true;
    last_ = timings;
    ++captures_;
    log::info("reflection probes: ", probes_.size(), " captured at ", ps.faceSize, "^2, capture ", timings.captureMs,
              " ms, prefilter ", timings.prefilterMs, " ms");
    return timings;
}

// The settings a capture renders with: the default method and IBL mode (whatever the frame uses), the frame's
// common parameters (exposure, ambient, env.intensity / rotation, lod...), and nothing that needs this camera or
// other frames: no probes (no probe sees another), no shadows (the maps are fitted to the main camera, not to a
// probe's six faces, so a capture sees direct light unshadowed: docs/reflection_probes.md), no ambient occlusion,
// no TAA and no image pipeline.
static RenderSettings captureSettings(const RenderSettings& frame) {
    RenderSettings settings;
    settings.common = frame.common;
    for (const char* off : {"probes.enabled=0", "shadow.enabled=0", "ao.enabled=0", "aa=off", "lighting.split_glinty=0"})
        settings.apply(off);
    return settings;
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
    GLuint array = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &array);
    specular_ = gl::Texture(array);
    glTextureStorage3D(array, kLevels, GL_RGBA32F, size, size, GLsizei(6 * 2 * probes_.size()));
    setCubeSampling(array);
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

FrameImage ReflectionProbes::image(bool active) const {
    const bool any = active && !probes_.empty() && specular_;
    return {.textures = {any ? specular_.id() : 0}, .buffer = any ? probeBlock_.id() : emptyBlock_.id(),
            .width = faceSize_, .height = faceSize_};
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
