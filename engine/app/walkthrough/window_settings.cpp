#include "app/walkthrough/window_settings.h"

namespace glimmer {

RenderSettings windowRenderSettings(const RenderSettings& requested, bool softwareRenderer, bool screenshotRun) {
    RenderSettings settings = requested;
    const bool software = softwareRenderer && !screenshotRun;
    // Material textures read trilinearly: llvmpipe's anisotropic filtering was about half the frame at render
    // scale 0.25 (docs/performance.md).
    if (software && !settings.isSet(param::texture_anisotropy)) settings.apply("texture_anisotropy=1");
    // Shadows at every second pixel (shadow.half_res, docs/shadows.md#cost), at the price of shadow and light
    // features under two pixels.
    if (software && !settings.isSet(param::shadow_half_res)) settings.apply("shadow.half_res=1");
    // Ambient occlusion at every second pixel (ao.half_res, docs/ambient_occlusion.md#half-resolution-aohalf_res).
    if (software && !settings.isSet(param::ao_half_res)) settings.apply("ao.half_res=1");
    // TAA resolved at the render size, its post passes (bloom, exposure, tone mapping) there too, with the window's
    // Catmull-Rom upscale after them (taa.upsample=0): at scale 0.25 in a 1280x720 window the upsampling resolve and
    // the post passes at the window's size took about half of the frame (docs/performance.md). GPUs keep TAA
    // upsampling.
    if (software && !settings.isSet(param::taa_upsample)) settings.apply("taa.upsample=0");
    // Geometry at the level of detail that keeps its error within a pixel of the render size (lod.pixel_error=1):
    // the G-buffer's vertex work is serial on llvmpipe.
    if (software && !settings.isSet(param::lod_pixel_error)) settings.apply("lod.pixel_error=1");
    // Every window shades glinty and other pixels with separate programs (render/frame/lighting_pass.h).
    if (!screenshotRun && !settings.isSet(param::lighting_split_glinty)) settings.apply("lighting.split_glinty=1");
    return settings;
}

}  // namespace glimmer
