// HDR radiance to display: exposure, ACES-fitted curve (Narkowicz 2015), sRGB encoding.
// Debug views (u_viewport.w != 0) are shown without tone mapping, clamped, so channels read directly; the albedo
// (a colour) is sRGB-encoded like every PNG colour, so it displays as the base colour it is.
#include "common/bindings.glsl"
#include "common/frame.glsl"

layout(binding = UNIT_TONEMAP_HDR) uniform sampler2D t_hdr;
in vec2 v_ndc;
layout(location = 0) out vec4 o_color;

vec3 acesFitted(vec3 x) {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    vec3 hdr = texelFetch(t_hdr, ivec2(gl_FragCoord.xy), 0).rgb;
    int view = u_viewport.w;
    vec3 display;
    if (view == VIEW_FINAL) display = linearToSrgb(acesFitted(hdr * u_exposure.x));
    else if (view == VIEW_ALBEDO) display = linearToSrgb(hdr);
    else if (view == VIEW_NORMAL || view == VIEW_TANGENT) display = hdr * 0.5 + 0.5;
    else if (view == VIEW_UV) display = vec3(fract(hdr.xy), 0.0);
    else display = clamp(hdr, 0.0, 1.0);
    o_color = vec4(display, 1.0);
}
