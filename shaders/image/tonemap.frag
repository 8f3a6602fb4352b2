// HDR radiance to display: bloom mixed in (Jimenez 2014: a lerp towards the blurred image keeps energy),
// exposure (manual stops times the metered exposure when exposure=auto), a tone curve (image/tone_curves.glsl),
// sRGB encoding. Debug views (u_viewport.w != 0) are shown without any of that, clamped, so channels read directly; the albedo
// (a colour) is sRGB-encoded like every PNG colour, so it displays as the base colour it is; depth and footprint,
// whose values lie far outside 0..1, are mapped into it (below).
#include "common/bindings.glsl"
#include "common/frame.glsl"
#include "image/tone_curves.glsl"

layout(binding = UNIT_TONEMAP_HDR) uniform sampler2D t_hdr;
layout(binding = UNIT_TONEMAP_BLOOM) uniform sampler2D t_bloom;   // half resolution, bilinear
layout(std430, binding = BINDING_EXPOSURE_STATE) readonly buffer ExposureState { float u_meteredEv; float u_targetEv; };

layout(location = 0) uniform int u_toneCurve;       // TONEMAP_*
layout(location = 1) uniform float u_bloomStrength; // 0: no bloom (t_bloom is not read)
layout(location = 2) uniform int u_autoExposure;    // 1: multiply by 2^u_meteredEv
layout(location = 3) uniform float u_bloomScale;    // 1 / bloom levels (t_bloom holds their sum)

in vec2 v_ndc;
layout(location = 0) out vec4 o_color;

void main() {
    vec3 hdr = texelFetch(t_hdr, ivec2(gl_FragCoord.xy), 0).rgb;
    int view = u_viewport.w;
    vec3 display;
    if (view == VIEW_FINAL) {
        if (u_bloomStrength > 0.0)
            hdr = mix(hdr, textureLod(t_bloom, gl_FragCoord.xy / vec2(u_viewport.xy), 0.0).rgb * u_bloomScale,
                      u_bloomStrength);
        float exposure = u_exposure.x * (u_autoExposure != 0 ? exp2(u_meteredEv) : 1.0);
        display = linearToSrgb(applyToneCurve(u_toneCurve, hdr * exposure));
    } else if (view == VIEW_ALBEDO) display = linearToSrgb(hdr);
    else if (view == VIEW_NORMAL || view == VIEW_TANGENT) display = hdr * 0.5 + 0.5;
    else if (view == VIEW_UV) display = vec3(fract(hdr.xy), 0.0);
    // Distances in metres on a log scale (0 m black, 1 m 0.125, 15 m 0.5, 255 m and beyond white): clamped raw
    // metres were white past 1 m. The EXR keeps the metres.
    else if (view == VIEW_DEPTH) display = vec3(clamp(log2(1.0 + hdr.r) / 8.0, 0.0, 1.0));
    // Footprint: R the anisotropy ratio (>= 1) as log2(ratio) / 4 (1 black, 16 full), G the LOD log2(minor axis in
    // UV) from -16 (black) to 0 (full); B method-specific, clamped. Clamped raw values were red or magenta
    // everywhere. The EXR keeps the raw values. A ratio below 1 is no footprint (the background, or a method
    // without one): black, not LOD 0's full green.
    else if (view == VIEW_FOOTPRINT)
        display = hdr.r < 1.0 ? vec3(0.0)
                              : clamp(vec3(log2(hdr.r) / 4.0, (hdr.g + 16.0) / 16.0, hdr.b), 0.0, 1.0);
    else display = clamp(hdr, 0.0, 1.0);
    o_color = vec4(display, 1.0);
}
