#include "render/shadows/shadow_maps.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "common/bindings.glsl"
#include "render/shadows/shadow_projections.h"

namespace glimmer {
namespace {

// std140 mirror of ShadowBlock in shaders/shadows/shadows.glsl.
struct ShadowBlockData {
    glm::mat4 views[kMaxShadowViews];
    glm::vec4 viewInfo[kMaxShadowViews];    // texel world size, layer, perspective (0/1), array (0 sun, 1 local)
    glm::ivec4 lights[kMaxShadowLights];    // kind, first view, view count, unused
    glm::vec4 filter;                       // filter radius, normal bias, depth bias (texels), enabled
    glm::vec4 mapSizes;                     // 1 / sun size, 1 / local size, sun size, local size
    glm::ivec4 mask;                        // G-buffer pixels per mask texel, slots, mask layers
    glm::ivec4 slotLights[kMaxShadowSlots / 4];   // light index of each slot
    glm::vec4 soft;                         // near plane of the local views, widest penumbra (texels)
};
static_assert(sizeof(ShadowBlockData) == kMaxShadowViews * 80 + kMaxShadowLights * 16 + 48 + kMaxShadowSlots * 4 + 16);

// Kinds of ShadowBlock.lights[].x (shaders/shadows/shadows.glsl).
constexpr int kShadowNone = 0, kShadowCascades = 1, kShadowCube = 2, kShadowSpot = 3;

// Point, spot and area lights: perspective views from their position (an area light's centre).
bool isLocal(const Light& light) { return light.type != LightType::Directional; }
// Size for soft shadows (shaders/shadows/shadows.glsl shadowPcssLocal): the radius of a point or spot light, of an
// area light's disk of equal area (render/gpu_scene.cpp).
bool castsSoftShadows(const Light& light) { return light.radius > 0.0f || light.isArea(); }
// Views of a local light's shadow: one for a spot narrow enough, else the six faces of a cube.
int localViewCount(const Light& light) {
    return light.type == LightType::Spot && light.outerConeAngle <= kMaxSpotViewHalfAngle ? 1 : 6;
}

// Guard band of a view, in texels: the PCF taps reach filterRadius + 1 texels (bilinear) from the point; a soft
// shadow's kernel up to kMaxPenumbraTexels.
float guardTexels(const ShadowSettings& s) { return s.filterRadius + 2.0f; }
float guardTexels(const ShadowSettings& s, const Light& light) {
    return castsSoftShadows(light) ? std::max(s.filterRadius, kMaxPenumbraTexels) + 2.0f : guardTexels(s);
}

uint64_t fnv(uint64_t hash, const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
    return hash;
}
template <typename T> uint64_t fnv(uint64_t hash, const T& value) { return fnv(hash, &value, sizeof(T)); }

gl::Texture createDepthArray(int size, int layers) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    glTextureStorage3D(id, 1, GL_DEPTH_COMPONENT32F, size, size, std::max(layers, 1));
    // Hardware 2x2 compare with bilinear weights; reversed Z: a receiver at or nearer the light (>=) is lit.
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(id, GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
    return gl::Texture(id);
}

}  // namespace

ShadowSettings shadowSettingsOf(const RenderSettings& settings) {
    ShadowSettings s;
    s.enabled = settings.value(param::shadow_enabled) > 0.5f;
    s.mapSize = int(settings.value(param::shadow_map_size));
    s.cascades = std::clamp(int(settings.value(param::shadow_cascades)), 1, kMaxCascades);
    s.filterRadius = settings.value(param::shadow_filter_radius);
    s.depthBias = settings.value(param::shadow_bias);
    s.normalBias = settings.value(param::shadow_normal_bias);
    s.slopeBias = settings.value(param::shadow_slope_bias);
    s.distance = settings.value(param::shadow_distance);
    s.pointMapSize = int(settings.value(param::shadow_point_map_size));
    s.cache = settings.value(param::shadow_cache) > 0.5f;
    s.halfResMask = settings.value(param::shadow_half_res) > 0.5f;
    return s;
}

ShadowMaps::ShadowMaps() {
    block_ = gl::createBuffer(sizeof(ShadowBlockData), nullptr);
    GLuint fb = 0;
    glCreateFramebuffers(1, &fb);
    framebuffer_ = gl::Framebuffer(fb);
    glNamedFramebufferDrawBuffer(fb, GL_NONE);
    glNamedFramebufferReadBuffer(fb, GL_NONE);
}

void ShadowMaps::ensureArrays() {
    int sunLayers = std::max(int(suns_.size()) * settings_.cascades, 1);
    int localLayers = 0;
    for (const LocalState& local : locals_) localLayers += local.viewCount;
    localLayers = std::max(localLayers, 1);
    int sunSize = settings_.enabled && !suns_.empty() ? settings_.mapSize : 1;
    int localSize = settings_.enabled && !locals_.empty() ? settings_.pointMapSize : 1;
    if (!sunArray_ || sunLayers != sunLayers_ || sunSize != sunSize_) {
        sunArray_ = createDepthArray(sunSize, sunLayers);
        sunLayers_ = sunLayers, sunSize_ = sunSize;
        for (SunState& sun : suns_) sun.valid = false;
    }
    if (!localArray_ || localLayers != localLayers_ || localSize != localSize_) {
        localArray_ = createDepthArray(localSize, localLayers);
        // The same depths read without comparison (the soft shadows' blocker search): a view with its own state.
        GLuint view = 0;
        glGenTextures(1, &view);
        glTextureView(view, GL_TEXTURE_2D_ARRAY, localArray_.id(), GL_DEPTH_COMPONENT32F, 0, 1, 0, localLayers);
        glTextureParameteri(view, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(view, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(view, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(view, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureParameteri(view, GL_TEXTURE_COMPARE_MODE, GL_NONE);
        localDepthView_ = gl::Texture(view);
        localLayers_ = localLayers, localSize_ = localSize;
        for (LocalState& local : locals_) local.valid = false;
    }
}

void ShadowMaps::prepare(const Scene& scene, const GpuScene& gpuScene, const Camera& camera, float aspect,
                         const RenderSettings& renderSettings) {
    settings_ = shadowSettingsOf(renderSettings);
    stats_ = {};
    views_.clear();
    // Per light: kind, first view, view count, mask slot (-1: unshadowed).
    // Records are indexed like the GPU's lights (scene.h gpuLightOrder: punctual lights, then area lights).
    const std::vector<size_t> order = gpuLightOrder(scene.lights);
    std::vector<glm::ivec4> records(std::min(scene.lights.size(), size_t(kMaxShadowLights)),
                                    glm::ivec4(kShadowNone, 0, 0, -1));
    slots_ = 0;
    slotLights_.clear();
    slotFilters_.clear();
    if (!settings_.enabled) {
        suns_.clear();
        locals_.clear();
        ensureArrays();
        upload(records);
        return;
    }

    // What the cached maps depend on apart from the lights: the geometry (instances, the materials' alpha masks
    // and sidedness) and the parameters that change what is rasterized.
    uint64_t key = fnv(1469598103934665603ull, gpuScene.serial());
    for (const Instance& instance : scene.instances) {
        key = fnv(key, instance.mesh);
        key = fnv(key, instance.material);
        key = fnv(key, instance.transform);
    }
    for (const Material& m : scene.materials) {
        key = fnv(key, m.alphaCutoff);
        key = fnv(key, m.doubleSided);
        key = fnv(key, m.baseColorTexture);
    }
    for (float v : {float(settings_.mapSize), float(settings_.pointMapSize), float(settings_.cascades),
                    settings_.slopeBias, settings_.distance})
        key = fnv(key, v);
    if (key != contentKey_ || !settings_.cache) {
        for (SunState& sun : suns_) sun.valid = false;
        for (LocalState& local : locals_) local.valid = false;
        contentKey_ = key;
    }

    size_t directional = 0, local = 0;
    for (size_t i = 0; i < records.size(); ++i) {
        const Light& light = scene.lights[order[i]];
        if (light.type == LightType::Directional && directional < size_t(kMaxShadowedDirectional)) ++directional;
        if (isLocal(light) && local < size_t(kMaxShadowedLocal)) {
            if (local >= locals_.size()) locals_.emplace_back();
            if (locals_[local].viewCount != localViewCount(light)) locals_[local] = LocalState{};
            locals_[local].viewCount = localViewCount(light);
            ++local;
        }
    }
    suns_.resize(directional);
    locals_.resize(local);
    ensureArrays();

    directional = local = 0;
    int localLayer = 0;
    for (size_t i = 0; i < records.size(); ++i) {
        const Light& light = scene.lights[order[i]];
        if (light.type == LightType::Directional && directional < suns_.size()) {
            records[i] = {kShadowCascades, int(views_.size()), settings_.cascades, slots_++};
            slotLights_.push_back(int(i));
            slotFilters_.push_back(ShadowFilter::Cascades);
            fitSun(suns_[directional], light.vector, scene, gpuScene, camera, aspect,
                   int(directional) * settings_.cascades);
            ++directional;
        } else if (isLocal(light) && local < locals_.size()) {
            LocalState& state = locals_[local];
            records[i] = {state.viewCount == 1 ? kShadowSpot : kShadowCube, int(views_.size()), state.viewCount,
                          slots_++};
            slotLights_.push_back(int(i));
            // The size the mask's shader filters with: the light's GPU record (a point or spot light's radius, an
            // area light's equivalent disk).
            slotFilters_.push_back(gpuLight(light).spotOffsetRange.z > 0.0f ? ShadowFilter::Pcss : ShadowFilter::Pcf);
            fitLocal(state, light, localLayer);
            localLayer += state.viewCount;
            ++local;
        }
    }
    stats_.views = int(views_.size());
    upload(records);
}

void ShadowMaps::fitSun(SunState& sun, const glm::vec3& towardLight, const Scene& scene, const GpuScene& gpuScene,
                        const Camera& camera, float aspect, int firstLayer) {
    const glm::vec3 direction = glm::normalize(towardLight);
    if (!sun.valid || direction != sun.towardLight || int(sun.windows.size()) != settings_.cascades) {
        sun.towardLight = direction;
        sun.basis = lightBasis(direction);
        // The scene's light-space bounds, from the chunk boxes of every instance: they fix the depth range (one
        // for all cascades, so every caster between the light and a receiver is in the map) and clip the
        // cascades' needed regions (a far cascade wider than the scene then never moves).
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const Instance& instance : scene.instances) {
            if (instance.mesh >= gpuScene.meshCount()) continue;
            const glm::mat4 toLight = glm::mat4(sun.basis) * instance.transform;
            for (const MeshChunk& chunk : gpuScene.meshChunks(instance.mesh))
                for (int corner = 0; corner < 8; ++corner) {
                    glm::vec3 p((corner & 1) ? chunk.boundsMax.x : chunk.boundsMin.x,
                                (corner & 2) ? chunk.boundsMax.y : chunk.boundsMin.y,
                                (corner & 4) ? chunk.boundsMax.z : chunk.boundsMin.z);
                    glm::vec3 q = glm::vec3(toLight * glm::vec4(p, 1.0f));
                    lo = glm::min(lo, q);
                    hi = glm::max(hi, q);
                }
        }
        if (lo.x > hi.x) lo = hi = glm::vec3(0.0f);
        float pad = 0.01f * std::max(hi.z - lo.z, 1.0f) + 0.05f;
        sun.sceneRect = {glm::vec2(lo), glm::vec2(hi)};
        sun.depthMin = lo.z - pad;
        sun.depthMax = hi.z + pad;
        sun.windows.assign(size_t(settings_.cascades), CascadeWindow{});
        sun.valid = true;
    }
    const std::vector<float> splits = cascadeSplits(camera.nearPlane, settings_.distance, settings_.cascades);
    for (int k = 0; k < settings_.cascades; ++k) {
        BoundingSphere sphere =
            cascadeSphere(camera.position, camera.verticalFovDegrees, aspect, splits[size_t(k) + 1]);
        LightRect needed = neededRect(sun.basis, sphere, sun.sceneRect);
        CascadeWindow fitted = fitCascadeWindow(needed, sphere.radius, kCascadeMargin, settings_.mapSize);
        CascadeWindow& cached = sun.windows[size_t(k)];
        // Reuse while the size is the same (same fov, aspect, splits) and the needed region is still inside.
        bool reuse = cached.halfExtent == fitted.halfExtent && cached.mapSize == fitted.mapSize &&
                     windowCovers(cached, needed, guardTexels(settings_));
        ShadowView view;
        view.array = ShadowArray::Sun;
        view.layer = firstLayer + k;
        view.dirty = !reuse;
        if (!reuse) cached = fitted;
        view.viewProjection = cascadeViewProjection(sun.basis, cached, sun.depthMin, sun.depthMax);
        view.texelWorld = cached.texelSize();
        views_.push_back(view);
    }
}

void ShadowMaps::fitLocal(LocalState& local, const Light& light, int firstLayer) {
    const bool spot = local.viewCount == 1;
    const glm::vec3 position = light.vector;
    const glm::vec3 direction = spot ? glm::normalize(light.spotDirection) : glm::vec3(0.0f);
    const float guard = guardTexels(settings_, light);
    const float tanHalf = spot ? spotViewTanHalf(light.outerConeAngle, settings_.pointMapSize, guard)
                               : cubeFaceTanHalf(settings_.pointMapSize, guard);
    const bool reuse =
        local.valid && local.position == position && local.direction == direction && local.tanHalf == tanHalf;
    local.position = position;
    local.direction = direction;
    local.tanHalf = tanHalf;
    local.valid = true;
    for (int face = 0; face < local.viewCount; ++face) {
        ShadowView view;
        view.array = ShadowArray::Local;
        view.layer = firstLayer + face;
        view.perspective = true;
        view.dirty = !reuse;
        view.viewProjection =
            perspectiveShadowView(position, spot ? direction : cubeFaceDirection(face), tanHalf, kLocalNearPlane);
        view.texelWorld = perspectiveTexelPerMetre(tanHalf, settings_.pointMapSize);
        views_.push_back(view);
    }
}

void ShadowMaps::upload(const std::vector<glm::ivec4>& lightRecords) {
    static ShadowBlockData data;   // 6 KB: kept off the stack
    std::memset(&data, 0, sizeof(data));
    for (size_t v = 0; v < views_.size() && v < size_t(kMaxShadowViews); ++v) {
        const ShadowView& view = views_[v];
        data.views[v] = view.viewProjection;
        data.viewInfo[v] = {view.texelWorld, float(view.layer), view.perspective ? 1.0f : 0.0f, float(int(view.array))};
    }
    for (size_t i = 0; i < lightRecords.size(); ++i) data.lights[i] = lightRecords[i];
    data.filter = {settings_.filterRadius, settings_.normalBias, settings_.depthBias, settings_.enabled ? 1.0f : 0.0f};
    data.mapSizes = {1.0f / float(sunSize_), 1.0f / float(localSize_), float(sunSize_), float(localSize_)};
    data.mask = {maskStep(), slots_, maskLayers(), 0};
    for (int slot = 0; slot < slots_; ++slot) data.slotLights[slot / 4][slot % 4] = slotLights_[size_t(slot)];
    data.soft = {kLocalNearPlane, kMaxPenumbraTexels, 0.0f, 0.0f};
    glNamedBufferSubData(block_.id(), 0, sizeof(data), &data);
}

glm::ivec4 ShadowMaps::maskLayerFilters(int layer) const {
    glm::ivec4 filters(int(ShadowFilter::None));
    for (int c = 0; c < 4; ++c) {
        const size_t slot = size_t(4 * layer + c);
        if (slot < slotFilters_.size()) filters[c] = int(slotFilters_[slot]);
    }
    return filters;
}

void ShadowMaps::ensureMask(int width, int height) {
    const int step = maskStep();
    const glm::ivec2 size((std::max(width, 1) + step - 1) / step, (std::max(height, 1) + step - 1) / step);
    const int layers = std::max(maskLayers(), 1);
    if (mask_ && size == maskSize_ && layers == maskTextureLayers_) return;
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
    glTextureStorage3D(id, 1, GL_RGBA8, size.x, size.y, layers);   // visibility in [0, 1]; 0 and 1 exact
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    mask_ = gl::Texture(id);
    if (!maskFramebuffer_) {
        GLuint fb = 0;
        glCreateFramebuffers(1, &fb);
        maskFramebuffer_ = gl::Framebuffer(fb);
    }
    maskSize_ = size;
    maskTextureLayers_ = layers;
}

GLuint ShadowMaps::maskFramebuffer(int layer) {
    glNamedFramebufferTextureLayer(maskFramebuffer_.id(), GL_COLOR_ATTACHMENT0, mask_.id(), 0,
                                   std::clamp(layer, 0, maskTextureLayers_ - 1));
    return maskFramebuffer_.id();
}

FrameImage ShadowMaps::mapsImage() const {
    return {.textures = {sunArray_.id(), localArray_.id(), localDepthView_.id()}, .buffer = block_.id(),
            .width = sunSize_, .height = sunSize_};
}

FrameImage ShadowMaps::maskImage() const {
    if (!mask_) return {};
    return {.textures = {mask_.id()}, .width = maskSize_.x, .height = maskSize_.y};
}

void bindShadowInputs(const FrameImage& maps, const FrameImage& mask) {
    glBindBufferBase(GL_UNIFORM_BUFFER, BINDING_SHADOWS, maps.buffer);
    glBindTextureUnit(UNIT_SHADOW_SUN, maps.texture(0));
    glBindTextureUnit(UNIT_SHADOW_LOCAL, maps.texture(1));
    glBindTextureUnit(UNIT_SHADOW_LOCAL_DEPTH, maps.texture(2));   // the local depths without compare (soft shadows)
    glBindTextureUnit(UNIT_SHADOW_MASK, mask.texture(0));
}

GLuint ShadowMaps::framebufferFor(const ShadowView& view) {
    GLuint texture = view.array == ShadowArray::Sun ? sunArray_.id() : localArray_.id();
    glNamedFramebufferTextureLayer(framebuffer_.id(), GL_DEPTH_ATTACHMENT, texture, 0, view.layer);
    return framebuffer_.id();
}

}  // namespace glimmer
