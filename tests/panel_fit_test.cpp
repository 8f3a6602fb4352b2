// The window's panel fits the window at 960x540, 1280x720 and 1920x1080: for every method and with each section
// open in turn, every widget lies inside the window and the panel's visible area (nothing scrolled away), no two
// widgets overlap, no two glyphs overlap, text sits on whole pixels at the integer UI scale, and (through the real
// UI renderer) every glyph's pixels are exactly the font table's.
#include <gtest/gtest.h>

#include <cmath>

#include "core/files.h"
#include "gl/handles.h"
#include "platform/context.h"
#include "render/settings.h"
#include "support/test_needs.h"
#include "support/ui_canvas.h"
#include "ui/font.h"
#include "ui/settings_panel.h"
#include "ui/ui.h"
#include "ui/ui_renderer.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(PanelFit, GlContext);

namespace glimmer::ui {
namespace {

struct WindowSize {
    int width, height;
};
constexpr WindowSize kSizes[] = {{960, 540}, {1280, 720}, {1920, 1080}};

bool overlap(const Rect& a, const Rect& b) {
    return a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
}

WindowControls atriumControls() {
    WindowControls window;
    window.cameraNames = {"entrance", "court", "objects", "grazing", "arcade", "gallery", "overview"};
    window.sceneNames = {"plane90", "plane25", "heightmap90", "heightmap25", "sphere", "atrium"};
    window.sceneIndex = 5;
    // The Lights section's selector and a light's rows, with names as long as the atrium's.
    window.lightNames = {"1 sun", "2 sphere -10.5,2.25,-3.75", "3 sphere 10.5,2.25,-3.75", "4 rect -12.5,3.6,0.125"};
    window.lightIndex = 1;
    return window;
}

// Lays out one frame of the panel as the window does (panelLayout) with `open` as the open section.
void layoutPanel(Context& ui, RenderSettings& settings, WindowControls& window, WindowSize size, const std::string& open) {
    PanelLayout layout = panelLayout(size.width, size.height, kMaxStatsLines);
    ui.setOpenSection(kPanelId, open);
    ui.begin({}, size.width, size.height, layout.scale);
    settingsPanel(ui, settings, window, layout.x, layout.y, layout.maxHeight);
    ui.end();
}

std::vector<std::string> sectionNames(Context& ui, RenderSettings& settings, WindowControls& window) {
    layoutPanel(ui, settings, window, kSizes[1], "");
    std::vector<std::string> names;
    for (const auto& [label, rect] : ui.layout())
        if (label.rfind("+ ", 0) == 0) names.push_back(label.substr(2));
    return names;
}

TEST(PanelFit, EveryWidgetIsOnScreenWithoutOverlapAtThreeWindowSizes) {
    Context ui;
    WindowControls window = atriumControls();
    RenderSettings probe;
    std::vector<std::string> sections = sectionNames(ui, probe, window);
    ASSERT_GE(sections.size(), 6u);
    for (WindowSize size : kSizes)
        for (const GlintMethod& method : glintMethods())
            for (const std::string& open : sections) {
                RenderSettings settings;
                settings.method = method.id;
                layoutPanel(ui, settings, window, size, open);
                std::string where = std::to_string(size.width) + "x" + std::to_string(size.height) + " " +
                                    method.id + " [" + open + "]";
                std::optional<Rect> area = ui.panelArea(kPanelId);
                ASSERT_TRUE(area) << where;
                EXPECT_GE(area->x, 0.0f);
                EXPECT_LE(area->x + area->w, float(size.width)) << where;
                const auto& widgets = ui.layout();
                bool sawOpen = false;
                for (size_t i = 0; i < widgets.size(); ++i) {
                    const auto& [label, r] = widgets[i];
                    sawOpen |= label == "- " + open;
                    EXPECT_TRUE(r.w > 0 && r.h > 0) << where << " " << label;
                    EXPECT_TRUE(r.x >= area->x && r.y >= area->y && r.x + r.w <= area->x + area->w &&
                                r.y + r.h <= area->y + area->h)
                        << where << ": '" << label << "' is not on screen (" << r.x << "," << r.y << " " << r.w
                        << "x" << r.h << ")";
                    for (size_t j = 0; j < i; ++j)
                        EXPECT_FALSE(overlap(r, widgets[j].second)) << where << ": '" << label << "' overlaps '"
                                                                    << widgets[j].first << "'";
                }
                EXPECT_TRUE(sawOpen) << where;
                int scale = panelLayout(size.width, size.height, kMaxStatsLines).scale;
                std::vector<Rect> glyphs;
                for (const Quad& q : ui.drawList().quads()) {
                    if (q.glyph < 0) continue;
                    EXPECT_EQ(q.scale, scale) << where;
                    EXPECT_EQ(q.rect.x, std::floor(q.rect.x)) << where;
                    EXPECT_EQ(q.rect.y, std::floor(q.rect.y)) << where;
                    EXPECT_TRUE(q.glyph >= kFirstGlyph && q.glyph < kFirstGlyph + kGlyphCount) << where;
                    for (const Rect& other : glyphs) EXPECT_FALSE(overlap(q.rect, other)) << where << " glyph " << char(q.glyph);
                    glyphs.push_back(q.rect);
                }
                EXPECT_GT(glyphs.size(), 50u) << where;
            }
}

// Clicking a closed section's header opens it (from the next frame) and closes the open one; clicking the open
// one closes it.
TEST(PanelFit, ClickingASectionHeaderOpensItAndClosesTheOther) {
    Context ui;
    WindowControls window = atriumControls();
    RenderSettings settings;
    auto frame = [&](const Input& input) {
        PanelLayout layout = panelLayout(1280, 720, kMaxStatsLines);
        ui.begin(input, 1280, 720, layout.scale);
        settingsPanel(ui, settings, window, layout.x, layout.y, layout.maxHeight);
        ui.end();
    };
    frame({});
    EXPECT_EQ(ui.openSection(kPanelId), "Method (M)");
    ASSERT_TRUE(ui.widgetRect("+ Lights"));
    Input click;
    click.mouse = ui.widgetRect("+ Lights")->at(0.5f, 0.5f);
    click.mousePressed = click.mouseDown = true;
    frame(click);
    frame({});
    EXPECT_EQ(ui.openSection(kPanelId), "Lights");
    EXPECT_TRUE(ui.widgetRect("- Lights"));
    EXPECT_TRUE(ui.widgetRect("+ Method (M)"));
    EXPECT_FALSE(ui.widgetRect("method"));
    EXPECT_TRUE(ui.widgetRect("light.intensity"));
    click.mouse = ui.widgetRect("- Lights")->at(0.5f, 0.5f);
    frame(click);
    frame({});
    EXPECT_EQ(ui.openSection(kPanelId), "");
    EXPECT_FALSE(ui.widgetRect("light.intensity"));
}

// Integer scales by window height; at the three sizes the Method section of the method with the most
// parameters (wang2020) is all on screen (checked above), so the scale is the largest that allows it.
TEST(PanelFit, ScaleIsAnIntegerThatGrowsWithTheWindow) {
    EXPECT_EQ(panelLayout(960, 540, kMaxStatsLines).scale, 1);
    EXPECT_EQ(panelLayout(1280, 720, kMaxStatsLines).scale, 2);
    EXPECT_EQ(panelLayout(1920, 1080, kMaxStatsLines).scale, 2);
    EXPECT_EQ(panelLayout(640, 360, kMaxStatsLines).scale, 1);
}

using Canvas = test::UiCanvas;

// Every glyph of the panel, drawn by the UI renderer at each window size, matches the font table pixel for
// pixel: lit cells in the text colour, unlit ones not.
TEST(PanelFit, EveryLabelRendersFromTheFontTableAtThreeWindowSizes) {
    auto context = createHeadlessContext(Backend::Egl);
    {
        UiRenderer renderer(defaultShaderDir());
        for (WindowSize size : kSizes) {
            Context ui;
            WindowControls window = atriumControls();
            RenderSettings settings;
            settings.method = "deliot2023";
            layoutPanel(ui, settings, window, size, "Method (M)");
            Canvas canvas(size.width, size.height);
            glBindFramebuffer(GL_FRAMEBUFFER, canvas.framebuffer.id());
            renderer.draw(ui.drawList(), size.width, size.height);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            std::vector<uint8_t> p = canvas.pixels();
            auto at = [&](int x, int y) { return canvas.at(p, x, y); };
            size_t glyphs = 0, mismatches = 0;
            for (const Quad& q : ui.drawList().quads()) {
                if (q.glyph < 0) continue;
                ++glyphs;
                const GlyphRows& rows = glyphRows(char(q.glyph));
                for (int row = 0; row < kCellHeight; ++row)
                    for (int col = 0; col < kGlyphWidth; ++col) {
                        bool lit = (rows[size_t(row)] >> (kGlyphWidth - 1 - col)) & 1;
                        for (int s = 0; s < q.scale * q.scale; ++s) {
                            int x = int(q.rect.x) + col * q.scale + s % q.scale, y = int(q.rect.y) + row * q.scale + s / q.scale;
                            const uint8_t* px = at(x, y);
                            bool textColour = px[0] == q.color.r && px[1] == q.color.g && px[2] == q.color.b;
                            mismatches += lit != textColour;
                        }
                    }
            }
            EXPECT_GT(glyphs, 100u) << size.width;
            EXPECT_EQ(mismatches, 0u) << size.width << "x" << size.height;
        }
    }
}

// A method parameter that the glint material maps shows "material" until the user overrides it (the materials'
// values are in effect, not the spec default); an override, or a parameter no material maps, shows its number.
TEST(PanelFit, MaterialMappedMethodParametersSayMaterialUntilOverridden) {
    const GlintMethod& deliot = findGlintMethod("deliot2023");
    RenderSettings settings;
    settings.method = deliot.id;
    ASSERT_FALSE(deliot.materialMapping.empty());
    for (const ParamMapping& m : deliot.materialMapping)
        EXPECT_STREQ(methodParameterValueText(deliot, settings, m.param), "material") << m.param;
    EXPECT_EQ(methodParameterValueText(deliot, settings, "screen_space_scale"), nullptr);
    settings.methods[deliot.id]["log_density"] = 12.0f;
    EXPECT_EQ(methodParameterValueText(deliot, settings, "log_density"), nullptr);
    for (const GlintMethod& method : glintMethods())
        for (const ParamMapping& m : method.materialMapping)
            EXPECT_STREQ(methodParameterValueText(method, RenderSettings{}, m.param), "material")
                << method.id << "." << m.param;
}

}  // namespace
}  // namespace glimmer::ui
