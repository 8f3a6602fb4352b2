// The UI's embedded bitmap font: glyphs for printable ASCII (32..126) designed for this project, 5x8 pixels in a
// 6x8 cell (one blank column separates characters). Row 0 is the top; rows 0-6 hold capitals and digits, row 7
// holds descenders. The table is plain data so text layout and tests need no GL; ui_renderer uploads it.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace glimmer::ui {

constexpr int kGlyphWidth = 5;      // lit columns
constexpr int kCellWidth = 6;       // advance per character, in font pixels
constexpr int kCellHeight = 8;      // rows per glyph
constexpr int kFirstGlyph = 32;     // ' '
constexpr int kGlyphCount = 95;     // ' ' .. '~'

// Rows of one glyph: bit (kGlyphWidth - 1 - column) of rows[row] is lit. Characters outside printable ASCII
// map to '?'.
using GlyphRows = std::array<uint8_t, kCellHeight>;
const GlyphRows& glyphRows(char c);

// The whole table packed four rows per 32-bit word (row r of glyph g in word g*2 + r/4, byte r%4): the layout
// shaders/ui/ui.frag reads.
std::array<uint32_t, kGlyphCount * 2> packedGlyphTable();

// Width in screen pixels of `text` drawn at integer `scale` (no trailing spacing column).
int textWidth(std::string_view text, int scale);
// `text` in lines of at most `columns` characters, broken at spaces where possible (else inside a word).
std::vector<std::string> wrapText(const std::string& text, size_t columns);

}  // namespace glimmer::ui
