// UI overlay: filled rectangles, or glyphs of the embedded 5x8 font (engine/ui/font.cpp). Glyph rows are packed
// four per word: row r of glyph g is byte r % 4 of u_glyphRows[g * 2 + r / 4]; bit (4 - column) is lit.
const int FIRST_GLYPH = 32;
const int GLYPH_COUNT = 95;
#include "common/bindings.glsl"
layout(location = LOCATION_UI_GLYPH_ROWS) uniform uint u_glyphRows[GLYPH_COUNT * 2];

in vec2 v_fontPixel;
flat in vec4 v_color;
flat in int v_glyph;
layout(location = 0) out vec4 o_color;

void main() {
    if (v_glyph >= 0) {
        int column = clamp(int(v_fontPixel.x), 0, 4);
        int row = clamp(int(v_fontPixel.y), 0, 7);
        int glyph = clamp(v_glyph - FIRST_GLYPH, 0, GLYPH_COUNT - 1);
        uint rowBits = (u_glyphRows[glyph * 2 + row / 4] >> uint(8 * (row % 4))) & 0xffu;
        if (((rowBits >> uint(4 - column)) & 1u) == 0u) discard;
    }
    o_color = v_color;
}
