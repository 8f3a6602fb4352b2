// `glimmer render --compare m1,m2,...`: the same view rendered with smooth and each listed method, laid out side by
// side as one labelled image like the papers' comparison figures, with optional zoomed crops (nearest-neighbour
// insets below each tile, each crop framed on the tiles in its inset's colour). Labels are drawn on the CPU with
// the UI's bitmap font.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "offscreen/offscreen.h"

namespace glimmer::bench {

struct CropRect {
    int x = 0, y = 0, width = 0, height = 0;  // pixels of the render, (0,0) = top-left
};
// Parses "x,y,w,h"; throws UsageError naming --crop.
CropRect parseCrop(const std::string& text);

struct CompareTile {
    std::string method;
    int renderX = 0, renderY = 0;             // top-left of the render in the grid
    int labelX = 0, labelY = 0, labelHeight = 0;
    std::vector<CropRect> insets;             // where each crop's inset lies in the grid
};

struct CompareGrid {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;                // RGBA8 sRGB, top-down rows
    std::vector<CompareTile> tiles;
};

// Frame colours of crops 0..3 (repeating): red, light blue, green, yellow.
extern const uint8_t kCropColours[4][3];

// Font scale of the labels and the gap between tiles, in pixels.
constexpr int kCompareLabelScale = 2;
constexpr int kCompareGap = 4;

// Methods in grid order: smooth first, then `methods` in order (duplicates dropped); unknown ids throw.
std::vector<std::string> comparisonMethods(const std::vector<std::string>& methods);

// Renders `base` (its settings.method is ignored) once per method in one session and lays the tiles out.
CompareGrid renderComparison(const RenderRequest& base, const std::vector<std::string>& methods,
                             const std::vector<CropRect>& crops);

// Draws `text` (bitmap font, `scale` pixels per font pixel) into a top-down RGBA8 image; clipped at the edges.
void drawText(std::vector<uint8_t>& rgba, int width, int height, int x, int y, const std::string& text, int scale,
              const uint8_t colour[3]);

}  // namespace glimmer::bench
