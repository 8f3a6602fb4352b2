// The UI's one batched draw through the real GL pipeline (EGL, llvmpipe): glyph pixels must match the CPU font
// table exactly, rectangles must cover exactly their pixels, blending must follow alpha.
#include <gtest/gtest.h>

#include "core/files.h"
#include "gl/handles.h"
#include "platform/context.h"
#include "ui/font.h"
#include "ui/ui_renderer.h"
#include "support/ui_canvas.h"
#include "ui/settings_panel.h"
#include "core/clock.h"

#include <algorithm>
#include <cstdio>
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(UiRenderer, GlContext);

namespace glimmer::ui {
namespace {

using Canvas = test::UiCanvas;

TEST(UiRenderer, GlyphsAndRectanglesMatchTheFontTableInOneDraw) {
    auto context = createHeadlessContext(Backend::Egl);
    {
        UiRenderer renderer(defaultShaderDir());
        Canvas canvas(160, 40);
        DrawList list;
        list.fill({100, 4, 10, 6}, {0, 255, 0, 255});
        list.fill({120, 4, 10, 6}, {255, 255, 255, 128});  // half-transparent over black
        const std::string text = "Ag{9";
        const int scale = 2;
        list.text({4, 4}, text, {255, 0, 0, 255}, scale);
        glBindFramebuffer(GL_FRAMEBUFFER, canvas.framebuffer.id());
        renderer.draw(list, canvas.width, canvas.height);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        std::vector<uint8_t> p = canvas.pixels();

        size_t mismatches = 0;
        for (size_t i = 0; i < text.size(); ++i) {
            const GlyphRows& rows = glyphRows(text[i]);
            for (int row = 0; row < kCellHeight; ++row)
                for (int col = 0; col < kCellWidth; ++col) {
                    bool lit = col < kGlyphWidth && (rows[size_t(row)] >> (kGlyphWidth - 1 - col)) & 1;
                    for (int sy = 0; sy < scale; ++sy)
                        for (int sx = 0; sx < scale; ++sx) {
                            int x = 4 + int(i) * kCellWidth * scale + col * scale + sx, y = 4 + row * scale + sy;
                            mismatches += canvas.at(p, x, y)[0] != (lit ? 255 : 0);
                        }
                }
        }
        EXPECT_EQ(mismatches, 0u);
        EXPECT_EQ(canvas.at(p, 100, 4)[1], 255);
        EXPECT_EQ(canvas.at(p, 109, 9)[1], 255);
        EXPECT_EQ(canvas.at(p, 110, 9)[1], 0);
        EXPECT_EQ(canvas.at(p, 109, 10)[1], 0);
        EXPECT_NEAR(canvas.at(p, 125, 6)[0], 128, 1);
    }
}

// The whole settings panel at 1280x720 is one draw of a few thousand quads; time it (wall clock around glFinish,
// the only meaningful clock on llvmpipe) so the overlay's cost next to a frame is known.
TEST(UiRenderer, FullPanelIsOneDrawAndCheap) {
    auto context = createHeadlessContext(Backend::Egl);
    {
        UiRenderer renderer(defaultShaderDir());
        Canvas canvas(1280, 720);
        Context ui;
        RenderSettings settings;
        WindowControls window;
        window.cameraNames = {"front"};
        ui.begin({}, 1280, 720, 2);
        settingsPanel(ui, settings, window, 8, 8, 650);
        ui.textAt({8, 680}, std::string(100, 'x'), palette::kText);
        ui.end();
        size_t quads = ui.drawList().quads().size();
        EXPECT_GT(quads, 250u);  // the open Method section, the section headers and a stats line
        glBindFramebuffer(GL_FRAMEBUFFER, canvas.framebuffer.id());
        std::vector<double> ms;
        for (int i = 0; i < 15; ++i) {
            glFinish();
            Stopwatch clock;
            renderer.draw(ui.drawList(), 1280, 720);
            glFinish();
            ms.push_back(clock.elapsedMs());
        }
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        std::sort(ms.begin(), ms.end());
        std::printf("[ measure  ] UI overlay: %zu quads in one draw, median %.2f ms at 1280x720 (wall, glFinish)\n",
                    quads, ms[ms.size() / 2]);
        // The panel's pixels changed (the draw reached the target).
        std::vector<uint8_t> p = canvas.pixels();
        EXPECT_NE(canvas.at(p, 20, 20)[2], 0);
    }
}

}  // namespace
}  // namespace glimmer::ui
