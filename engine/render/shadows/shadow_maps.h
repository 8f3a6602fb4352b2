// Shadow maps of the scene's lights and the per-light visibility data the lighting pass reads
// (shaders/shadows/shadows.glsl). Every shadow is a set of views, each one layer of a 2D depth array:
// - directional lights (the sun): one orthographic view per cascade (render/shadows/shadow_cascades.h), in the sun array;
// - point lights (lanterns): six perspective views, the faces of a cube (render/shadows/shadow_projections.h), in the
//   local-light array;
// - spot lights: one perspective view along the axis fitted to the outer cone, in the same array (a spot wider
//   than kMaxSpotViewHalfAngle is shadowed like a point light: a single view would spread its texels too thin);
// - area lights (rect, disk, sphere): a cube at the light's centre, like a point light; their size (and a point
//   light's radius) gives soft shadows (shaders/shadows/shadows.glsl).
// prepare() decides each frame which views are still valid and which must be re-rendered (the shadow passes,
// render/shadows/shadow_map_pass.h, render only those): a view is re-rendered when the scene's geometry, the
// light or the map parameters changed, or, for a cascade, when the camera moved its needed region out of the
// cached square. On a still camera with static lights no view is rendered after the first frame.
#pragma once
#include <glad/gl.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "gl/handles.h"
#include "render/frame/frame_resources.h"
#include "render/gpu_scene.h"
#include "render/settings.h"
#include "render/shadows/shadow_cascades.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace glimmer {

// The shadow.* parameters (render/settings.cpp), read once per frame.
struct ShadowSettings {
    bool enabled = true;
    int mapSize = 2048;          // sun cascades, texels per side
    int cascades = 3;
    float filterRadius = 1.5f;   // PCF radius, texels
    float depthBias = 0.5f;      // receiver offset towards the light, texels
    float normalBias = 0.5f;     // receiver offset along the normal, texels x sin(angle between normal and light)
    float slopeBias = 3.0f;      // caster slope-scaled depth bias (glPolygonOffset factor)
    float distance = 40.0f;      // view depth covered by the cascades, metres
    int pointMapSize = 512;      // point-light cube faces, texels per side
    bool cache = true;           // false: every view is re-rendered every frame (measurements)
    bool halfResMask = false;    // shadow mask at every second pixel (render/shadows/shadow_mask_pass.h)
};
ShadowSettings shadowSettingsOf(const RenderSettings& settings);

// Limits: lights beyond them are unshadowed (visibility 1). Mirrored in shaders/shadows/shadows.glsl.
constexpr int kMaxShadowedDirectional = 4;
constexpr int kMaxShadowedLocal = 8;
constexpr int kMaxCascades = 4;
constexpr int kMaxShadowViews = kMaxShadowedDirectional * kMaxCascades + kMaxShadowedLocal * 6;
// Widest outer cone (half angle, radians) shadowed by one perspective view: at 60 degrees the map's edge texels
// are 4x the centre's in area (1 / cos^2); wider spots take a cube.
constexpr float kMaxSpotViewHalfAngle = 1.0471976f;
constexpr int kMaxShadowLights = 64;
// Shadowed lights: each has a slot in the shadow mask (RGBA8 array, four slots per layer).
constexpr int kMaxShadowSlots = kMaxShadowedDirectional + kMaxShadowedLocal;
static_assert(kMaxShadowSlots % 4 == 0);
// Extra square around each cascade's sphere, as a fraction of its radius: the camera may move this far before
// the cascade is re-rendered.
constexpr float kCascadeMargin = 0.25f;
// Near plane of the point lights' faces (metres): casters closer to a light than this cast no shadow.
constexpr float kLocalNearPlane = 0.05f;
// Widest soft-shadow kernel of a light with a size (texels of its views; shaders/shadows/shadows.glsl
// shadowPcssLocal): its views carry a guard band this wide.
constexpr float kMaxPenumbraTexels = 16.0f;

enum class ShadowArray : int { Sun = 0, Local = 1 };
// How the shadow mask filters a slot's light (shaders/shadows/shadows.glsl SHADOW_FILTER_*): the sun's cascades,
// PCF in a point or spot light's view, soft shadows (PCSS) for a light with a size.
enum class ShadowFilter : int { None = 0, Cascades = 1, Pcf = 2, Pcss = 3 };

struct ShadowView {
    ShadowArray array = ShadowArray::Sun;
    int layer = 0;
    glm::mat4 viewProjection{1.0f};
    // Orthographic: metres per texel. Perspective: metres per texel per metre of view depth.
    float texelWorld = 0.0f;
    bool perspective = false;
    bool dirty = true;            // must be rendered this frame
};

// Binds the shadow block, both depth arrays and the mask at the units of common/bindings.glsl (the shadow-mask and
// lighting passes).
void bindShadowInputs(const FrameImage& maps, const FrameImage& mask);

class ShadowMaps {
public:
    ShadowMaps();

    // Fits the views of every shadowed light for this frame and marks the ones to render; uploads the shadow
    // block. With shadow.enabled = 0 no view exists and every light's visibility is 1.
    void prepare(const Scene& scene, const GpuScene& gpuScene, const Camera& camera, float aspect,
                 const RenderSettings& settings);
    // What the frame's other passes read (FrameResource::ShadowMaps: both depth arrays and the shadow block;
    // FrameResource::ShadowMask), bound by bindShadowInputs().
    FrameImage mapsImage() const;
    FrameImage maskImage() const;
    // The shadow mask (render/shadows/shadow_mask_pass.h) for a width x height frame: an RGBA8 array of maskSize()
    // texels and maskLayers() layers holding every shadowed light's visibility (one channel per slot) at every
    // maskStep()-th pixel; reallocated when the size or the layer count changes. Then the framebuffer of `layer`.
    void ensureMask(int width, int height);
    GLuint maskFramebuffer(int layer);
    int maskStep() const { return settings_.halfResMask ? 2 : 1; }
    int maskLayers() const { return (slots_ + 3) / 4; }
    // The filters of mask layer `layer`'s four slots (ShadowFilter; None past the last slot): its program is
    // compiled for them (render/shadows/shadow_mask_pass.cpp).
    glm::ivec4 maskLayerFilters(int layer) const;
    glm::ivec2 maskSize() const { return maskSize_; }
    // Forgets every cached map (the next prepare() marks every view dirty): after the depth program was rebuilt.
    void invalidate() { contentKey_ = 0; }

    const ShadowSettings& settings() const { return settings_; }
    std::vector<ShadowView>& views() { return views_; }
    // A framebuffer with `view`'s layer as its depth attachment.
    GLuint framebufferFor(const ShadowView& view);
    int mapSizeOf(const ShadowView& view) const {
        return view.array == ShadowArray::Sun ? settings_.mapSize : settings_.pointMapSize;
    }

    // What the shadow passes did in the last frame (for --stats and the tests of the cache).
    struct Stats {
        int views = 0;                 // views in use
        int sunViewsRendered = 0, localViewsRendered = 0;
        size_t trianglesDrawn = 0;
    };
    Stats& stats() { return stats_; }
    const Stats& stats() const { return stats_; }

private:
    struct SunState {             // one shadowed directional light
        glm::vec3 towardLight{0.0f};
        glm::mat3 basis{1.0f};
        LightRect sceneRect;
        float depthMin = 0.0f, depthMax = 0.0f;
        std::vector<CascadeWindow> windows;   // cached squares (rendered)
        bool valid = false;
    };
    struct LocalState {           // one shadowed point or spot light
        glm::vec3 position{0.0f};
        glm::vec3 direction{0.0f};   // spot view: the axis; cube: unused (zero)
        float tanHalf = 0.0f;
        int viewCount = 6;           // 6: cube faces, 1: one spot view
        bool valid = false;
    };
    void ensureArrays();
    void fitSun(SunState& sun, const glm::vec3& towardLight, const Scene& scene, const GpuScene& gpuScene,
                const Camera& camera, float aspect, int firstLayer);
    void fitLocal(LocalState& local, const Light& light, int firstLayer);
    void upload(const std::vector<glm::ivec4>& lightRecords);

    ShadowSettings settings_;
    uint64_t contentKey_ = 0;     // scene geometry + map parameters the cached maps were rendered with
    std::vector<SunState> suns_;
    std::vector<LocalState> locals_;
    std::vector<ShadowView> views_;
    gl::Texture sunArray_, localArray_;
    gl::Texture localDepthView_;   // localArray_ read without compare (soft shadows' blocker search)
    int sunLayers_ = 0, localLayers_ = 0, sunSize_ = 0, localSize_ = 0;
    gl::Framebuffer framebuffer_;
    gl::Texture mask_;
    gl::Framebuffer maskFramebuffer_;
    glm::ivec2 maskSize_{0, 0};
    int maskTextureLayers_ = 0;
    int slots_ = 0;                          // shadowed lights this frame
    std::vector<int> slotLights_;            // light index of each slot
    std::vector<ShadowFilter> slotFilters_;  // filter of each slot
    gl::Buffer block_;
    Stats stats_;
};

}  // namespace glimmer
