// UI overlay: one instanced quad per rectangle or glyph (engine/ui/ui_renderer.cpp). Pixel coordinates,
// origin top-left, y down.
layout(location = 0) in vec4 a_rect;     // x, y, width, height in pixels
layout(location = 1) in uint a_color;    // RGBA8 packed, red in the low byte
layout(location = 2) in int a_glyph;     // ASCII code, or -1 for a filled rectangle
layout(location = 3) in float a_scale;   // screen pixels per font pixel
#include "common/bindings.glsl"
layout(location = LOCATION_UI_SCREEN_SIZE) uniform vec2 u_screenSize;

out vec2 v_fontPixel;
flat out vec4 v_color;
flat out int v_glyph;

void main() {
    vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1);
    vec2 pixel = a_rect.xy + corner * a_rect.zw;
    v_fontPixel = corner * a_rect.zw / a_scale;
    v_color = unpackUnorm4x8(a_color);
    v_glyph = a_glyph;
    gl_Position = vec4(pixel.x / u_screenSize.x * 2.0 - 1.0, 1.0 - pixel.y / u_screenSize.y * 2.0, 0.0, 1.0);
}
