#include "ui/window_defaults.h"

namespace glimmer::ui {

float windowStartScale(bool softwareRenderer) { return softwareRenderer ? 0.25f : 1.0f; }

void applyWindowDefaults(RenderSettings& settings, bool softwareRenderer) {
    auto setDefault = [&](const CommonParamKey& key, const char* assignment) {
        if (!settings.isSet(key)) settings.apply(assignment);
    };
    // The game image (docs/image.md): TAA, a little bloom, auto exposure.
    setDefault(param::aa, "aa=taa");
    setDefault(param::bloom_strength, "bloom.strength=0.04");
    if (!settings.isSet(param::exposure) && !settings.isSet(param::exposure_auto)) settings.apply("exposure=auto");
    // Every window shades glinty and other pixels with separate programs (render/frame/lighting_pass.h).
    setDefault(param::lighting_split_glinty, "lighting.split_glinty=1");
    // Glints are sub-pixel: below render scale 1 each render pixel shades the sparkle of an output pixel's footprint
    // at its centre, so the glints a player sees do not thin out with the scale (issue 39; docs/window.md).
    setDefault(param::lighting_glint_footprint, "lighting.glint_footprint=output");
    if (!softwareRenderer) return;
    // Material textures trilinear: llvmpipe's anisotropic filtering was about half the frame at render scale 0.25
    // (docs/performance.md).
    setDefault(param::texture_anisotropy, "texture_anisotropy=1");
    // Shadows and ambient occlusion at every second pixel (docs/shadows.md#cost,
    // docs/ambient_occlusion.md#half-resolution-aohalf_res).
    setDefault(param::shadow_half_res, "shadow.half_res=1");
    setDefault(param::ao_half_res, "ao.half_res=1");
    // TAA resolved at the render size, its post passes there too, with the window's Catmull-Rom upscale after them:
    // at scale 0.25 in a 1280x720 window the upsampling resolve and the post passes at the window's size took about
    // half of the frame (docs/performance.md). GPUs keep TAA upsampling.
    setDefault(param::taa_upsample, "taa.upsample=0");
    // The geometry at the level of detail that keeps its error within a pixel of the render size: the G-buffer's
    // vertex work is serial on llvmpipe.
    setDefault(param::lod_pixel_error, "lod.pixel_error=1");
}

}  // namespace glimmer::ui
