#include "bench/compare.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "glints/methods.h"
#include "ui/font.h"

namespace glimmer::bench {

CropRect parseCrop(const std::string& text) {
    std::vector<int> v;
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, ',')) {
        char* end = nullptr;
        long n = std::strtol(part.c_str(), &end, 10);
        if (part.empty() || *end != '\0' || n < 0 || n > 16384)
            throw UsageError("--crop: expected x,y,w,h (non-negative integers), got '" + text + "'");
        v.push_back(int(n));
    }
    if (v.size() != 4 || v[2] == 0 || v[3] == 0)
        throw UsageError("--crop: expected x,y,w,h with w and h > 0, got '" + text + "'");
    return {v[0], v[1], v[2], v[3]};
}

std::vector<std::string> comparisonMethods(const std::vector<std::string>& methods) {
    std::vector<std::string> order = {"smooth"};
    for (const std::string& id : methods) {
        findGlintMethod(id);
        if (std::find(order.begin(), order.end(), id) == order.end()) order.push_back(id);
    }
    return order;
}

void drawText(std::vector<uint8_t>& rgba, int width, int height, int x, int y, const std::string& text, int scale,
              const uint8_t colour[3]) {
    for (size_t k = 0; k < text.size(); ++k) {
        const ui::GlyphRows& rows = ui::glyphRows(text[k]);
        int originX = x + int(k) * ui::kCellWidth * scale;
        for (int row = 0; row < ui::kCellHeight; ++row)
            for (int col = 0; col < ui::kGlyphWidth; ++col) {
                if (!(rows[row] >> (ui::kGlyphWidth - 1 - col) & 1)) continue;
                for (int sy = 0; sy < scale; ++sy)
                    for (int sx = 0; sx < scale; ++sx) {
                        int px = originX + col * scale + sx, py = y + row * scale + sy;
                        if (px < 0 || py < 0 || px >= width || py >= height) continue;
                        uint8_t* p = &rgba[(size_t(py) * width + px) * 4];
                        p[0] = colour[0];
                        p[1] = colour[1];
                        p[2] = colour[2];
                        p[3] = 255;
                    }
            }
    }
}

// Distinct outline colours for the crops, so each inset can be matched to its region.
const uint8_t kCropColours[4][3] = {{255, 80, 80}, {80, 200, 255}, {120, 255, 120}, {255, 220, 60}};

CompareGrid renderComparison(const RenderRequest& base, const std::vector<std::string>& methodIds,
                             const std::vector<CropRect>& crops, const std::vector<CustomTile>& custom) {
    const int w = base.width, h = base.height;
    for (const CropRect& c : crops)
        if (c.x + c.width > w || c.y + c.height > h)
            throw UsageError("--crop: " + std::to_string(c.x) + "," + std::to_string(c.y) + "," +
                             std::to_string(c.width) + "," + std::to_string(c.height) + " lies outside the " +
                             std::to_string(w) + "x" + std::to_string(h) + " render");
    std::vector<std::string> methods = comparisonMethods(methodIds);

    // Integer zoom per crop: as large as fits the tile width and the render height.
    std::vector<int> zoom;
    int insetRows = 0;
    for (const CropRect& c : crops) {
        zoom.push_back(std::max(1, std::min((w - 2) / c.width, h / c.height)));
        insetRows += c.height * zoom.back() + 2 + kCompareGap;
    }
    auto customTile = [&](const std::string& id) -> const CustomTile* {
        for (const CustomTile& c : custom)
            if (c.method == id) return &c;
        return nullptr;
    };
    bool captions = false;
    for (const std::string& id : methods) captions = captions || (customTile(id) && customTile(id)->caption);
    // A caption line (font scale 1) under the labels when a tile has one.
    const int captionHeight = captions ? ui::kCellHeight + 4 : 0;
    const int labelHeight = ui::kCellHeight * kCompareLabelScale + 8 + captionHeight;
    CompareGrid grid;
    int n = int(methods.size());
    grid.width = n * w + (n + 1) * kCompareGap;
    grid.height = kCompareGap + labelHeight + h + kCompareGap + insetRows;
    grid.rgba.assign(size_t(grid.width) * grid.height * 4, 0);
    for (size_t i = 0; i < grid.rgba.size(); i += 4) {
        grid.rgba[i] = grid.rgba[i + 1] = grid.rgba[i + 2] = 24;
        grid.rgba[i + 3] = 255;
    }
    auto put = [&](int x, int y, const uint8_t* rgb) {
        if (x < 0 || y < 0 || x >= grid.width || y >= grid.height) return;
        uint8_t* p = &grid.rgba[(size_t(y) * grid.width + x) * 4];
        p[0] = rgb[0];
        p[1] = rgb[1];
        p[2] = rgb[2];
        p[3] = 255;
    };

    RenderRequest request = base;
    request.settings.method = methods.front();
    OffscreenSession session(request);
    const uint8_t white[3] = {240, 240, 240};
    for (int t = 0; t < n; ++t) {
        request.settings.method = methods[t];
        const CustomTile* special = customTile(methods[t]);
        RenderResult result = special ? special->render(session, request) : session.render(request);
        CompareTile tile;
        tile.method = methods[t];
        tile.renderX = kCompareGap + t * (w + kCompareGap);
        tile.labelX = tile.renderX + 2;
        tile.labelY = kCompareGap + 4;
        tile.labelHeight = labelHeight;
        tile.renderY = kCompareGap + labelHeight;
        drawText(grid.rgba, grid.width, grid.height, tile.labelX, tile.labelY, tile.method, kCompareLabelScale, white);
        if (special && special->caption)
            drawText(grid.rgba, grid.width, grid.height, tile.labelX, tile.labelY + ui::kCellHeight * kCompareLabelScale + 4,
                     special->caption(session, request), 1, white);
        // Render rows are bottom-up; the grid is top-down.
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) put(tile.renderX + x, tile.renderY + y, &result.display[(size_t(h - 1 - y) * w + x) * 4]);
        // Mark each crop on the tile with a 1-pixel frame just outside the region, in the inset's colour, as the
        // papers' figures do (the region itself stays untouched).
        for (size_t c = 0; c < crops.size(); ++c) {
            const CropRect& crop = crops[c];
            for (int y = crop.y - 1; y <= crop.y + crop.height; ++y)
                for (int x = crop.x - 1; x <= crop.x + crop.width; ++x) {
                    bool edge = x == crop.x - 1 || y == crop.y - 1 || x == crop.x + crop.width || y == crop.y + crop.height;
                    if (edge && x >= 0 && y >= 0 && x < w && y < h) put(tile.renderX + x, tile.renderY + y, kCropColours[c % 4]);
                }
        }
        int insetY = tile.renderY + h + kCompareGap;
        for (size_t c = 0; c < crops.size(); ++c) {
            const CropRect& crop = crops[c];
            int k = zoom[c], iw = crop.width * k, ih = crop.height * k;
            CropRect inset{tile.renderX + (w - iw) / 2, insetY + 1, iw, ih};
            for (int y = -1; y <= ih; ++y)  // 1-pixel outline in the crop's colour
                for (int x = -1; x <= iw; ++x)
                    if (x < 0 || y < 0 || x == iw || y == ih) put(inset.x + x, inset.y + y, kCropColours[c % 4]);
            for (int y = 0; y < ih; ++y)
                for (int x = 0; x < iw; ++x) {
                    int sx = crop.x + x / k, sy = crop.y + y / k;  // top-down source pixel
                    put(inset.x + x, inset.y + y, &result.display[(size_t(h - 1 - sy) * w + sx) * 4]);
                }
            tile.insets.push_back(inset);
            insetY += ih + 2 + kCompareGap;
        }
        grid.tiles.push_back(tile);
    }
    return grid;
}

}  // namespace glimmer::bench
