#include "render/ao/ambient_occlusion.h"

#include "common/bindings.glsl"
#include "core/cache_file.h"
#include "core/error.h"
#include "render/frame/pass_timer.h"

namespace glimmer {

AoSettings AoSettings::from(const RenderSettings& s) {
    AoSettings ao;
    ao.enabled = s.value(param::ao_enabled) > 0.5f;
    ao.screen = s.value(param::ao_screen) > 0.5f;
    ao.sky = s.value(param::ao_sky) > 0.5f;
    ao.denoise = s.value(param::ao_denoise) > 0.5f;
    ao.multiBounce = s.value(param::ao_multibounce) > 0.5f;
    ao.halfRes = s.value(param::ao_half_res) > 0.5f;
    ao.radius = s.value(param::ao_radius);
    ao.power = s.value(param::ao_power);
    ao.falloff = s.value(param::ao_falloff);
    ao.slices = int(s.value(param::ao_slices));
    ao.steps = int(s.value(param::ao_steps));
    ao.bake.cellSize = s.value(param::ao_sky_cell);
    ao.bake.directions = 2 * int(s.value(param::ao_sky_rays));
    return ao;
}

AmbientOcclusion::AmbientOcclusion() : white_(gl::createConstantTexture(1.0f, 1.0f, 1.0f, 1.0f)) {}

std::vector<PassTiming> AmbientOcclusion::prepare(const RenderSettings& settings, const Scene& scene,
                                                  uint64_t sceneSerial, int width, int height) {
    settings_ = AoSettings::from(settings);
    std::vector<PassTiming> ran;
    if (!settings_.enabled) return ran;
    const int w = (width + step() - 1) / step(), h = (height + step() - 1) / step();
    if (width != width_ || height != height_ || w != targetWidth_ || h != targetHeight_) {
        width_ = width;
        height_ = height;
        targetWidth_ = w;
        targetHeight_ = h;
        raw_ = gl::createTexture2D(GL_R16F, w, h);
        resolved_ = gl::createTexture2D(GL_RGBA16F, w, h);
        rawFbo_ = gl::createFramebuffer("ao raw", {raw_.id()});
        resolvedFbo_ = gl::createFramebuffer("ao resolved", {resolved_.id()});
    }
    const std::string params = settings_.bake.text();
    if (settings_.sky && (sceneSerial != bakedSerial_ || params != bakedParams_)) {
        lastBake_ = ao::loadOrBakeSkyVisibility(scene, settings_.bake, cache::defaultCacheDir());
        sky_ = lastBake_.grid;
        bakedSerial_ = sceneSerial;
        bakedParams_ = params;
        skyTexture_ = {};
        if (!sky_.empty()) {
            GLuint id = 0;
            glCreateTextures(GL_TEXTURE_3D, 1, &id);
            skyTexture_ = gl::Texture(id);
            glTextureStorage3D(id, 1, GL_RGBA32F, sky_.dims.x, sky_.dims.y, sky_.dims.z);
            glTextureSubImage3D(id, 0, 0, 0, 0, sky_.dims.x, sky_.dims.y, sky_.dims.z, GL_RGBA, GL_FLOAT,
                                sky_.probes.data());
            glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
        ran.push_back({lastBake_.fromCache ? "ao.sky_load" : "ao.sky_bake", lastBake_.milliseconds, 0.0});
    }
    return ran;
}

void AmbientOcclusion::bindSky(GLuint program) const {
    const bool on = settings_.sky && !sky_.empty() && skyTexture_;
    glBindTextureUnit(UNIT_AO_SKY, on ? skyTexture_.id() : 0);
    glProgramUniform4f(program, 8, sky_.origin.x, sky_.origin.y, sky_.origin.z, sky_.cellSize);
    glProgramUniform4i(program, 9, sky_.dims.x, sky_.dims.y, sky_.dims.z, on ? 1 : 0);
}

}  // namespace glimmer
