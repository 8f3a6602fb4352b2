// Ambient occlusion of the environment / ambient term (docs/ambient_occlusion.md): the targets and baked data
// that the two AO passes (render/ao/gtao_pass.h, ao_resolve_pass.h) share, and what the lighting pass reads.
// - Small scale: GTAO (shaders/ao/gtao.frag) into a raw visibility target at the internal resolution, or at every
//   second pixel in x and y with ao.half_res (common/plane_aware_upsample.glsl).
// - Large scale: the sky visibility baked once per static scene (ao/sky_visibility.h), uploaded as a 3D texture.
// - The resolve pass writes occlusionTexture(): rgb the factor on the environment term, a the visibility.
// With ao.enabled = 0 the lighting pass reads a 1 x 1 white texture (no cost, no change).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "gl/handles.h"
#include "render/ao/sky_visibility.h"
#include "render/settings.h"
#include "scene/scene.h"

namespace glimmer {

struct PassTiming;

struct AoSettings {
    bool enabled = true, screen = true, sky = true, denoise = true, multiBounce = true;
    bool halfRes = false;   // GTAO and resolve at every second pixel, interpolated by the lighting pass
    float radius = 1.0f, power = 1.0f, falloff = 0.8f;
    int slices = 2, steps = 4;
    ao::SkyVisibilityParams bake;
    static AoSettings from(const RenderSettings& settings);
};

class AmbientOcclusion {
public:
    AmbientOcclusion();

    // Per frame, before the passes: reads the ao.* parameters, (re)allocates the targets and, when the sky term
    // is on and `sceneSerial` (GpuScene::serial) or the bake parameters changed, loads or bakes the sky
    // visibility (blocking, progress on stderr). Returns the bake / load time when one ran (for --stats).
    std::vector<PassTiming> prepare(const RenderSettings& settings, const Scene& scene, uint64_t sceneSerial,
                                    int width, int height);
    const AoSettings& settings() const { return settings_; }

    // G-buffer pixels per texel of the raw and resolved targets (2 at ao.half_res) and their size.
    int step() const { return settings_.halfRes ? 2 : 1; }
    int targetWidth() const { return targetWidth_; }
    int targetHeight() const { return targetHeight_; }
    GLuint rawFramebuffer() const { return rawFbo_.id(); }
    GLuint rawTexture() const { return raw_.id(); }
    GLuint resolveFramebuffer() const { return resolvedFbo_.id(); }
    // What the lighting pass binds at UNIT_AMBIENT_OCCLUSION: the resolved factor, or white when AO is off.
    GLuint occlusionTexture() const { return settings_.enabled ? resolved_.id() : white_.id(); }

    // Binds the sky probes at UNIT_AO_SKY and sets the lookup uniforms (locations 8, 9) of `program`.
    void bindSky(GLuint program) const;
    const ao::SkyVisibilityGrid& skyGrid() const { return sky_; }
    const ao::SkyVisibilityResult& lastBake() const { return lastBake_; }

private:
    AoSettings settings_;
    int width_ = 0, height_ = 0, targetWidth_ = 0, targetHeight_ = 0;
    gl::Texture raw_, resolved_, white_, skyTexture_;
    gl::Framebuffer rawFbo_, resolvedFbo_;
    ao::SkyVisibilityGrid sky_;
    ao::SkyVisibilityResult lastBake_;
    uint64_t bakedSerial_ = 0;
    std::string bakedParams_;
};

}  // namespace glimmer
