// UI without GL: font data, slider mapping, widget layout and hit-testing driven by synthetic input, the
// generated settings panel (method selector, per-method sliders, common parameters), camera control.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "glints/glint_mapping.h"
#include "glints/method_cycle.h"
#include "glints/methods.h"
#include "render/aov.h"
#include "common/aov_ids.glsl"
#include "render/settings.h"
#include "ui/camera_controller.h"
#include "ui/font.h"
#include "ui/settings_panel.h"
#include "ui/ui.h"

namespace glimmer::ui {
namespace {

constexpr int kScreenW = 1280, kScreenH = 720;

// Runs one frame of a panel built by `build` with `input`.
template <class Build>
void frame(Context& ui, const Input& input, Build&& build, int scale = 1, float maxHeight = 700.0f) {
    ui.begin(input, kScreenW, kScreenH, scale);
    ui.beginPanel("test", 10.0f, 20.0f, 30, maxHeight);
    build();
    ui.endPanel();
    ui.end();
}

Input clickAt(glm::vec2 p) {
    Input in;
    in.mouse = p;
    in.mousePressed = true;
    in.mouseDown = true;
    return in;
}

ParamSpec linearSpec() {
    ParamSpec s;
    s.name = "linear";
    s.minValue = 0.0f;
    s.maxValue = 10.0f;
    s.defaultValue = 5.0f;
    return s;
}

TEST(UiFont, EveryPrintableGlyphIsDistinctAndLit) {
    std::set<GlyphRows> seen;
    for (int c = kFirstGlyph + 1; c < kFirstGlyph + kGlyphCount; ++c) {
        const GlyphRows& rows = glyphRows(char(c));
        int lit = 0;
        for (uint8_t r : rows) lit += __builtin_popcount(r);
        EXPECT_GT(lit, 0) << "glyph '" << char(c) << "' is empty";
        EXPECT_TRUE(seen.insert(rows).second) << "glyph '" << char(c) << "' duplicates another";
        for (uint8_t r : rows) EXPECT_LT(r, 1u << kGlyphWidth) << "glyph '" << char(c) << "' is wider than 5";
    }
    for (uint8_t r : glyphRows(' ')) EXPECT_EQ(r, 0);
    EXPECT_EQ(glyphRows('\t'), glyphRows('?'));
}

TEST(UiFont, PackedTableMatchesRowsInTheShaderLayout) {
    auto packed = packedGlyphTable();
    for (int g = 0; g < kGlyphCount; ++g)
        for (int row = 0; row < kCellHeight; ++row)
            EXPECT_EQ((packed[size_t(g * 2 + row / 4)] >> (8 * (row % 4))) & 0xffu,
                      glyphRows(char(g + kFirstGlyph))[size_t(row)]);
    EXPECT_EQ(textWidth("", 2), 0);
    EXPECT_EQ(textWidth("ab", 2), (2 * kCellWidth - 1) * 2);
}

TEST(UiDrawList, TextEmitsOneQuadPerVisibleCharacter) {
    DrawList list;
    list.text({100, 50}, "a b", palette::kText, 2);
    ASSERT_EQ(list.quads().size(), 2u);
    EXPECT_EQ(list.quads()[0].glyph, 'a');
    EXPECT_FLOAT_EQ(list.quads()[1].rect.x, 100.0f + 2 * kCellWidth * 2);
    EXPECT_FLOAT_EQ(list.quads()[1].rect.h, float(kCellHeight * 2));
}

TEST(UiSlider, MappingIsLinearLogarithmicAndSnapsIntegers) {
    ParamSpec lin = linearSpec();
    EXPECT_FLOAT_EQ(sliderValue(lin, 0.25f), 2.5f);
    EXPECT_FLOAT_EQ(sliderFraction(lin, 7.5f), 0.75f);
    EXPECT_FLOAT_EQ(sliderValue(lin, -1.0f), 0.0f);
    EXPECT_FLOAT_EQ(sliderValue(lin, 2.0f), 10.0f);

    ParamSpec log;
    log.minValue = 0.01f;
    log.maxValue = 100.0f;
    log.logScale = true;
    EXPECT_NEAR(sliderValue(log, 0.5f), 1.0f, 1e-5f);
    EXPECT_NEAR(sliderValue(log, 0.75f), 10.0f, 1e-4f);
    EXPECT_NEAR(sliderFraction(log, 0.1f), 0.25f, 1e-6f);
    for (float t : {0.0f, 0.1f, 0.33f, 0.9f, 1.0f}) EXPECT_NEAR(sliderFraction(log, sliderValue(log, t)), t, 1e-5f);

    ParamSpec logFromZero = log;  // a zero minimum stays reachable at the left end
    logFromZero.minValue = 0.0f;
    logFromZero.maxValue = 1e6f;
    EXPECT_EQ(sliderValue(logFromZero, 0.0f), 0.0f);
    EXPECT_FLOAT_EQ(logFloor(logFromZero), 1e-3f);
    EXPECT_NEAR(sliderValue(logFromZero, 1.0f / 3.0f), 1.0f, 1e-4f);

    ParamSpec integer = lin;
    integer.integer = true;
    EXPECT_EQ(sliderValue(integer, 0.26f), 3.0f);
    EXPECT_EQ(sliderStep(integer, 3.0f, 1), 4.0f);
    EXPECT_EQ(sliderStep(integer, 10.0f, 1), 10.0f);
    EXPECT_NEAR(sliderStep(lin, 5.0f, -1), 4.9f, 1e-5f);
    EXPECT_EQ(formatSliderValue(integer, 3.0f), "3");
    EXPECT_EQ(formatSliderValue(lin, 0.123456f), "0.1235");
}

TEST(UiSlider, ClickAtAKnownPlaceSetsTheExpectedValue) {
    Context ui;
    ParamSpec spec = linearSpec();
    float value = 5.0f;
    frame(ui, {}, [&] { ui.slider("linear", spec, value); });
    auto rect = ui.widgetRect("linear");
    ASSERT_TRUE(rect);
    EXPECT_GT(rect->w, 100.0f);

    Edit edit = Edit::None;
    frame(ui, clickAt(rect->at(0.25f, 0.5f)), [&] { edit = ui.slider("linear", spec, value); });
    EXPECT_EQ(edit, Edit::Changed);
    EXPECT_NEAR(value, 2.5f, 1e-5f);
    EXPECT_TRUE(ui.mouseOverUi());

    // Dragging keeps editing the grabbed slider, even outside its row.
    Input drag;
    drag.mouse = {rect->at(0.75f, 0.0f).x, rect->y + 300.0f};
    drag.mouseDown = true;
    frame(ui, drag, [&] { ui.slider("linear", spec, value); });
    EXPECT_NEAR(value, 7.5f, 1e-5f);

    // Released: moving the mouse changes nothing.
    Input hover;
    hover.mouse = rect->at(0.1f, 0.5f);
    frame(ui, hover, [&] { edit = ui.slider("linear", spec, value); });
    EXPECT_EQ(edit, Edit::None);
    EXPECT_NEAR(value, 7.5f, 1e-5f);

    // Right click asks for a reset and leaves the value to the caller.
    Input right;
    right.mouse = rect->at(0.5f, 0.5f);
    right.rightPressed = true;
    frame(ui, right, [&] { edit = ui.slider("linear", spec, value); });
    EXPECT_EQ(edit, Edit::Reset);
    EXPECT_NEAR(value, 7.5f, 1e-5f);
}

TEST(UiSlider, LogScaleSliderClickMovesInLogSpace) {
    Context ui;
    ParamSpec spec;
    spec.name = "density";
    spec.minValue = 1.0f;
    spec.maxValue = 1e4f;
    spec.logScale = true;
    float value = 1.0f;
    frame(ui, {}, [&] { ui.slider("density", spec, value); });
    auto rect = ui.widgetRect("density");
    ASSERT_TRUE(rect);
    frame(ui, clickAt(rect->at(0.5f, 0.5f)), [&] { ui.slider("density", spec, value); });
    EXPECT_NEAR(value, 100.0f, 100.0f * 1e-4f);
    frame(ui, clickAt(rect->at(0.25f, 0.5f)), [&] { ui.slider("density", spec, value); });
    EXPECT_NEAR(value, 10.0f, 10.0f * 1e-4f);
}

TEST(UiWidgets, ClicksOutsideWidgetsChangeNothing) {
    Context ui;
    ParamSpec spec = linearSpec();
    float value = 5.0f;
    bool box = false;
    auto build = [&] {
        ui.slider("linear", spec, value);
        ui.checkbox("box", box);
    };
    frame(ui, {}, build);
    frame(ui, clickAt({900.0f, 400.0f}), build);
    EXPECT_EQ(value, 5.0f);
    EXPECT_FALSE(box);
    EXPECT_FALSE(ui.mouseOverUi());
    auto rect = ui.widgetRect("box");
    frame(ui, clickAt(rect->at(0.9f, 0.5f)), build);
    EXPECT_TRUE(box);
}

TEST(UiWidgets, SelectorStepsBackOnTheLeftHalfAndForwardOnTheRight) {
    Context ui;
    std::vector<std::string> options = {"a", "b", "c"};
    int index = 0;
    bool changed = false;
    auto build = [&] { changed = ui.selector("pick", options, index); };
    frame(ui, {}, build);
    Rect row = *ui.widgetRect("pick");
    glm::vec2 right = row.at(0.95f, 0.5f), left = row.at(0.5f, 0.5f);  // value area is the right 55%
    frame(ui, clickAt(right), build);
    EXPECT_TRUE(changed);
    EXPECT_EQ(index, 1);
    frame(ui, clickAt(right), build);
    frame(ui, clickAt(right), build);
    EXPECT_EQ(index, 0);  // wraps
    frame(ui, clickAt(left), build);
    EXPECT_EQ(index, 2);
}

TEST(UiWidgets, KeyboardFocusAndAdjustWork) {
    Context ui;
    ParamSpec spec = linearSpec();
    spec.integer = true;
    float first = 1.0f, second = 1.0f;
    bool pressed = false;
    auto build = [&] {
        ui.slider("first", spec, first);
        ui.slider("second", spec, second);
        pressed = ui.button("go");
    };
    frame(ui, {}, build);
    Input down;
    down.focusMove = 1;
    frame(ui, down, build);  // focus: first
    frame(ui, down, build);  // focus: second
    EXPECT_EQ(ui.focusIndex(), 1);
    Input adjust;
    adjust.adjust = 1;
    frame(ui, adjust, build);
    EXPECT_EQ(first, 1.0f);
    EXPECT_EQ(second, 2.0f);
    frame(ui, down, build);
    Input enter;
    enter.activate = true;
    frame(ui, enter, build);
    EXPECT_TRUE(pressed);
    frame(ui, down, build);  // wraps to the first widget
    EXPECT_EQ(ui.focusIndex(), 0);

    Context fresh;  // several presses within one (slow) frame all count
    auto buildFresh = [&] {
        fresh.slider("first", spec, first);
        fresh.slider("second", spec, second);
        fresh.button("go");
    };
    frame(fresh, {}, buildFresh);
    Input twice;
    twice.focusMove = 2;
    twice.adjust = 3;
    frame(fresh, twice, buildFresh);
    EXPECT_EQ(fresh.focusIndex(), 1);
    EXPECT_EQ(second, 5.0f);
}

TEST(UiWidgets, TallPanelsScrollAndHideRowsOutOfView) {
    Context ui;
    ParamSpec spec = linearSpec();
    std::vector<float> values(40, 5.0f);
    auto build = [&] {
        for (size_t i = 0; i < values.size(); ++i) ui.slider("s" + std::to_string(i), spec, values[i]);
    };
    float maxHeight = 200.0f;
    frame(ui, {}, build, 1, maxHeight);
    Rect last = *ui.widgetRect("s39");
    EXPECT_GT(last.y, 20.0f + maxHeight);  // laid out below the visible area
    frame(ui, clickAt(last.at(0.5f, 0.5f)), build, 1, maxHeight);
    EXPECT_EQ(values[39], 5.0f);  // not hittable while hidden
    Input wheel;
    wheel.mouse = {50.0f, 100.0f};
    wheel.scroll = -100.0f;  // towards the user: scroll down to the end
    frame(ui, wheel, build, 1, maxHeight);
    frame(ui, {}, build, 1, maxHeight);
    Rect scrolled = *ui.widgetRect("s39");
    EXPECT_LE(scrolled.y + scrolled.h, 20.0f + maxHeight);
    frame(ui, clickAt(scrolled.at(0.0f, 0.5f)), build, 1, maxHeight);
    EXPECT_EQ(values[39], 0.0f);
}

// A made-up method table: the panel must give any method sliders from its ParamSpecs alone.
std::vector<GlintMethod> fakeMethods() {
    GlintMethod smooth{"smooth", "Smooth", "GLINT_METHOD_SMOOTH", "glints/smooth.glsl", "-", {}};
    ParamSpec count{"count", 2.0f, 1.0f, 8.0f, "an integer", {}, true};
    ParamSpec density{"density", 10.0f, 1.0f, 1e4f, "a density", {}, false, true};
    ParamSpec mode{"mode", 0.0f, 0.0f, 2.0f, "an enumeration", {"one", "two", "three"}};
    GlintMethod fake{"fake", "Fake method", "GLINT_METHOD_FAKE", "glints/fake.glsl", "-", {count, density, mode}};
    return {smooth, fake};
}

PanelResult panelFrame(Context& ui, const Input& input, RenderSettings& settings, WindowControls& window,
                       const std::vector<GlintMethod>& methods) {
    ui.begin(input, kScreenW, kScreenH, 2);
    PanelResult r = settingsPanel(ui, settings, window, 8.0f, 8.0f, 2000.0f, methods);
    ui.end();
    return r;
}

TEST(UiSettingsPanel, MethodSelectorSwitchesMethodAndGeneratesItsSliders) {
    Context ui;
    RenderSettings settings;
    WindowControls window;
    auto methods = fakeMethods();
    panelFrame(ui, {}, settings, window, methods);
    EXPECT_FALSE(ui.widgetRect("density"));
    Rect selector = *ui.widgetRect("method");
    PanelResult r = panelFrame(ui, clickAt(selector.at(0.95f, 0.5f)), settings, window, methods);
    EXPECT_TRUE(r.methodChanged);
    EXPECT_TRUE(r.settingsChanged);
    EXPECT_EQ(settings.method, "fake");

    panelFrame(ui, {}, settings, window, methods);
    ASSERT_TRUE(ui.widgetRect("count"));
    ASSERT_TRUE(ui.widgetRect("mode"));
    Rect density = *ui.widgetRect("density");
    r = panelFrame(ui, clickAt(density.at(0.75f, 0.5f)), settings, window, methods);
    EXPECT_TRUE(r.settingsChanged);
    EXPECT_FALSE(r.methodChanged);
    EXPECT_NEAR(settings.methods["fake"]["density"], 1000.0f, 1000.0f * 1e-4f);

    Rect count = *ui.widgetRect("count");
    panelFrame(ui, clickAt(count.at(0.5f, 0.5f)), settings, window, methods);
    EXPECT_EQ(settings.methods["fake"]["count"], 5.0f);  // 1 + 0.5 * 7 = 4.5 rounds to 5 (integer)

    Rect mode = *ui.widgetRect("mode");
    panelFrame(ui, clickAt(mode.at(0.95f, 0.5f)), settings, window, methods);
    EXPECT_EQ(settings.methods["fake"]["mode"], 1.0f);

    // Right click resets to the default: the value is removed from the settings.
    Input right;
    right.mouse = density.at(0.2f, 0.5f);
    right.rightPressed = true;
    panelFrame(ui, right, settings, window, methods);
    EXPECT_EQ(settings.methods["fake"].count("density"), 0u);
}

// Issue 39, 9: a parameter each material maps (deliot2023's log_density) shows the reference material's mapped
// value and one arrow press steps from there, not from the spec's default (16 -> 17 on every material).
TEST(UiSettingsPanel, MappedParameterStepsFromTheMaterialsValue) {
    const GlintMethod& deliot = findGlintMethod("deliot2023");
    const ParamSpec* spec = nullptr;
    for (const ParamSpec& p : deliot.params)
        if (p.name == "log_density") spec = &p;
    ASSERT_TRUE(spec);
    Material ice;
    ice.name = "ice";
    ice.glinty = true;
    ice.glint.density = 5e3f;   // far from the default's e^16 per UV area
    const float mapped = materialParams(deliot, ice, {}).at("log_density");
    ASSERT_GT(std::abs(mapped - spec->defaultValue), 3.0f) << "the test needs a mapped value away from the default";
    bool found = false;
    for (int k = 1; k < 60 && !found; ++k) {
        Context ui;
        RenderSettings settings;
        settings.method = "deliot2023";
        WindowControls window;
        window.mappedMaterial = ice;
        panelFrame(ui, {}, settings, window, glintMethods());
        Input step;
        step.focusMove = k;
        step.adjust = 1;
        panelFrame(ui, step, settings, window, glintMethods());
        auto values = settings.methods.find("deliot2023");
        if (values == settings.methods.end() || !values->second.count("log_density")) continue;
        found = true;
        EXPECT_NEAR(values->second.at("log_density"), sliderStep(*spec, mapped, 1), 1e-4f)
            << "mapped " << mapped << ", default " << spec->defaultValue;
    }
    EXPECT_TRUE(found) << "no focus position reached the log_density slider";
}

// Issue 39, 11: N walks every debug view once ("glintscale" is an alias of "extra", where N used to jump back to
// "final", so ao, shadow and clearcoat were out of reach), and Shift+N walks back.
TEST(UiWindowKeys, DebugViewCycleReachesEveryView) {
    std::set<int> all;
    for (const AovInfo& aov : aovTable()) all.insert(aov.viewId);
    std::set<int> seen;
    int view = VIEW_FINAL;
    for (size_t i = 0; i < all.size(); ++i) {
        int next = nextDebugView(view, 1).viewId;
        EXPECT_EQ(nextDebugView(next, -1).viewId, view);
        view = next;
        seen.insert(view);
    }
    EXPECT_EQ(view, VIEW_FINAL) << "one cycle visits each view once";
    EXPECT_EQ(seen, all);
    for (int wanted : {VIEW_AO, VIEW_SHADOW, VIEW_CLEARCOAT}) EXPECT_TRUE(seen.count(wanted)) << wanted;
}

// Issue 39, 11: Shift+B never puts the left side's method on the right side.
TEST(UiWindowKeys, SplitMethodCycleSkipsTheLeftMethod) {
    const auto& methods = glintMethods();
    ASSERT_GE(methods.size(), 3u);
    for (const GlintMethod& left : methods) {
        std::set<std::string> right;
        std::string at = methods[0].id == left.id ? methods[1].id : methods[0].id;
        for (size_t i = 0; i < methods.size(); ++i) {
            at = cycleGlintMethod(at, 1, left.id).id;
            EXPECT_NE(at, left.id);
            right.insert(at);
        }
        EXPECT_EQ(right.size(), methods.size() - 1) << left.id;
    }
    EXPECT_EQ(cycleGlintMethod(methods[0].id, 2).id, methods[2].id);
    EXPECT_EQ(cycleGlintMethod(methods[0].id, -1).id, methods.back().id);
}

// Issue 37: the Lights section edits one light at a time: the selector picks it, its rows write light.<N>.<field>
// (the --set keys), a right click removes the edit again.
TEST(UiSettingsPanel, LightsSectionEditsTheSelectedLight) {
    Context ui;
    RenderSettings settings;
    WindowControls window;
    Light sun, rect;
    rect.type = LightType::Rect;
    rect.vector = {1.0f, 2.0f, 3.0f};
    window.lightNames = lightSelectorNames({sun, rect});
    ASSERT_EQ(window.lightNames.size(), 2u);
    EXPECT_EQ(window.lightNames[0], "1 sun");
    EXPECT_EQ(window.lightNames[1], "2 rect 1,2,3");
    auto methods = fakeMethods();
    ui.setOpenSection(kPanelId, commonGroupTitle("light"));
    panelFrame(ui, {}, settings, window, methods);
    ASSERT_TRUE(ui.widgetRect("light.1.intensity"));
    EXPECT_FALSE(ui.widgetRect("light.2.intensity"));
    Rect selector = *ui.widgetRect("edit light");
    panelFrame(ui, clickAt(selector.at(0.95f, 0.5f)), settings, window, methods);
    EXPECT_EQ(window.lightIndex, 1);
    panelFrame(ui, {}, settings, window, methods);
    for (const ParamSpec& spec : lightEditParams()) EXPECT_TRUE(ui.widgetRect(lightEditKey(2, spec.name))) << spec.name;
    Rect size = *ui.widgetRect("light.2.size");
    PanelResult r = panelFrame(ui, clickAt(size.at(0.75f, 0.5f)), settings, window, methods);
    EXPECT_TRUE(r.settingsChanged);
    ASSERT_TRUE(settings.common.count("light.2.size"));
    EXPECT_GT(settings.common.at("light.2.size"), 1.0f);
    EXPECT_FALSE(settings.common.count("light.1.size"));
    Input right;
    right.mouse = size.at(0.2f, 0.5f);
    right.rightPressed = true;
    r = panelFrame(ui, right, settings, window, methods);
    EXPECT_TRUE(r.settingsChanged);
    EXPECT_FALSE(settings.common.count("light.2.size"));
}

TEST(UiSettingsPanel, CommonParametersAndDebugViewAreEditable) {
    Context ui;
    RenderSettings settings;
    WindowControls window;
    window.cameraNames = {"front", "side"};
    auto methods = fakeMethods();
    // Each common parameter shows in its group's section (one section is open at a time).
    for (const CommonParam& p : commonParams()) {
        std::string group = p.spec.name.find('.') == std::string::npos ? "" : p.spec.name.substr(0, p.spec.name.find('.'));
        ui.setOpenSection(kPanelId, commonGroupTitle(group));
        panelFrame(ui, {}, settings, window, methods);
        EXPECT_EQ(bool(ui.widgetRect(p.spec.name)), !panelHidesParameter(p.spec.name)) << p.spec.name;
    }
    ui.setOpenSection(kPanelId, commonGroupTitle("material"));
    panelFrame(ui, {}, settings, window, methods);

    const CommonParam* alpha = nullptr;
    for (const CommonParam& p : commonParams())
        if (p.spec.name == "material.alpha") alpha = &p;
    ASSERT_TRUE(alpha);
    Rect row = *ui.widgetRect("material.alpha");
    PanelResult r = panelFrame(ui, clickAt(row.at(0.5f, 0.5f)), settings, window, methods);
    EXPECT_TRUE(r.settingsChanged);
    ASSERT_TRUE(settings.isSet(param::material_alpha));
    EXPECT_NEAR(settings.value(param::material_alpha), sliderValue(alpha->spec, 0.5f), 1e-6f);

    ui.setOpenSection(kPanelId, commonGroupTitle(""));
    panelFrame(ui, {}, settings, window, methods);
    Rect view = *ui.widgetRect("debug view");
    panelFrame(ui, clickAt(view.at(0.95f, 0.5f)), settings, window, methods);
    EXPECT_EQ(settings.debugView, 1);

    ui.setOpenSection(kPanelId, "Scene, camera, window");
    panelFrame(ui, {}, settings, window, methods);
    Rect camera = *ui.widgetRect("camera (1-9)");
    r = panelFrame(ui, clickAt(camera.at(0.95f, 0.5f)), settings, window, methods);
    EXPECT_EQ(r.cameraRequested, 1);
    EXPECT_EQ(commonGroupTitle("material"), "Material overrides (all)");
    EXPECT_EQ(commonGroupTitle("zzz"), "zzz");
}

TEST(UiCamera, FlyCameraKeepsAnUnmovedCameraExactAndMovesAlongItsAxes) {
    Camera start;
    start.position = {0.3f, 1.7f, 2.9f};
    start.target = {0.1f, 0.2f, -0.4f};
    FlyCamera fly;
    fly.set(start);
    EXPECT_EQ(fly.camera().position, start.position);
    EXPECT_EQ(fly.camera().target, start.target);
    glm::vec3 forward = start.forward();
    fly.move({0.0f, 0.0f, 2.0f});
    EXPECT_NEAR(glm::length(fly.camera().position - (start.position + 2.0f * forward)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(fly.camera().forward() - forward), 0.0f, 1e-5f);
    fly.move({0.0f, 1.0f, 0.0f});  // Q/E move along world up
    EXPECT_NEAR(fly.camera().position.y, start.position.y + 2.0f * forward.y + 1.0f, 1e-5f);
    fly.set(start);
    fly.turn(0.0f, 10.0f);  // clamped below the pole
    EXPECT_NEAR(fly.camera().forward().y, std::sin(glm::radians(89.0f)), 1e-4f);
    fly.set(start);
    fly.turn(glm::radians(90.0f), 0.0f);
    EXPECT_NEAR(glm::dot(fly.camera().forward(), forward), forward.y * forward.y, 1e-4f);  // horizontal parts orthogonal
}

TEST(UiCamera, TurningACameraThatLooksStraightDownContinuesThePicture) {
    Camera top;  // as plane90's "top": looking down, screen up = -z
    top.position = {0, 2, 0};
    top.target = {0, 0, 0};
    top.up = {0, 0, -1};
    FlyCamera fly;
    fly.set(top);
    fly.move({1.0f, 0.0f, 0.0f});  // D moves to screen right = +x
    EXPECT_NEAR(fly.camera().position.x, 1.0f, 1e-6f);
    fly.set(top);
    fly.turn(0.0f, 0.1f);  // pitch up tilts the view towards the top of the screen (-z), without spinning
    glm::vec3 f = fly.camera().forward();
    EXPECT_LT(f.z, -0.05f);
    EXPECT_NEAR(f.x, 0.0f, 1e-4f);
    EXPECT_LT(f.y, -0.9f);
}

TEST(UiCamera, WalkthroughPathPassesThroughEveryCameraInOrder) {
    std::vector<Camera> cameras(3);
    cameras[0].position = {0, 1, 4};
    cameras[0].target = {0, 0, 0};
    cameras[1].position = {4, 1, 0};
    cameras[1].target = {0, 0.5f, 0};
    cameras[1].verticalFovDegrees = 30.0f;
    cameras[2].position = {0, 2, -4};
    cameras[2].target = {1, 0, 0};
    CameraPath path(cameras, 2.0f, 1.0f);
    // Segments last their length over the speed: sqrt(32) / 2 and sqrt(33) / 2 seconds.
    float arrivals[3] = {0.0f, std::sqrt(32.0f) / 2.0f, std::sqrt(32.0f) / 2.0f + std::sqrt(33.0f) / 2.0f};
    EXPECT_NEAR(path.duration(), arrivals[2], 1e-4f);
    for (int i = 0; i < 3; ++i) {
        Camera c = path.at(arrivals[i]);
        EXPECT_NEAR(glm::length(c.position - cameras[size_t(i)].position), 0.0f, 1e-4f) << i;
        EXPECT_NEAR(glm::length(c.forward() - cameras[size_t(i)].forward()), 0.0f, 1e-3f) << i;
        EXPECT_NEAR(c.verticalFovDegrees, cameras[size_t(i)].verticalFovDegrees, 1e-3f);
    }
    // Continuous: small time steps give small moves.
    glm::vec3 previous = path.at(0.0f).position;
    for (float t = 0.01f; t <= path.duration(); t += 0.01f) {
        glm::vec3 p = path.at(t).position;
        EXPECT_LT(glm::length(p - previous), 0.05f) << t;
        previous = p;
    }
    EXPECT_EQ(path.at(1e6f).position, cameras[2].position);
    EXPECT_TRUE(CameraPath({}).empty());
}

}  // namespace
}  // namespace glimmer::ui
