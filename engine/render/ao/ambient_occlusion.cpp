#include "render/ao/ambient_occlusion.h"

#include "common/bindings.glsl"
#include "core/cache_file.h"
#include "core/error.h"
#include "render/frame/pass_timer.h"

namespace glimmer {

AoSettings AoSettings::from(const RenderSettings& s) {
    AoSettings ao;
    ao.enabled = s.common_("ao.enabled") > 0.5f;
    ao.screen = s.common_("ao.screen") > 0.5f;
    ao.sky = s.common_("ao.sky") > 0.5f;
    ao.denoise = s.common_("ao.denoise") > 0.5f;
    ao.multiBounce = s.common_("ao.multibounce") > 0.5f;
    ao.halfRes = s.common_("ao.half_res") > 0.5f;
    ao.radius = s.common_("ao.radius");
    ao.power = s.common_("ao.power");
    ao.falloff = s.common_("ao.falloff");
    ao.slices = int(s.common_("ao.slices"));
    ao.steps = int(s.common_("ao.steps"));
    ao.bake.cellSize = s.common_("ao.sky_cell");
    ao.bake.directions = 2 * int(s.common_("ao.sky_rays"));
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
