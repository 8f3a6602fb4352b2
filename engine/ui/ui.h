// Immediate-mode widgets for the walkthrough window (no Dear ImGui). Each frame: begin(input), call widgets in
// order (they hit-test against this frame's input and return edits), end(). Layout and hit-testing produce a
// DrawList of plain quads and touch no GL, so tests drive widgets with synthetic input; ui_renderer draws the
// list in one batched call.
//
// Coordinates are framebuffer pixels, origin top-left, y down (as GLFW reports the cursor).
// Mouse: left click/drag edits, right click resets a parameter to its default, wheel scrolls a panel.
// Keyboard: Input::focusMove walks the focus through widgets, Input::adjust steps the focused one, activate
// presses it.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/params.h"

namespace glimmer::ui {

struct Rect {
    float x = 0, y = 0, w = 0, h = 0;
    bool contains(glm::vec2 p) const { return p.x >= x && p.x < x + w && p.y >= y && p.y < y + h; }
    // The point at fractions (fx, fy) of the rectangle.
    glm::vec2 at(float fx, float fy) const { return {x + fx * w, y + fy * h}; }
};

struct Color {
    uint8_t r = 0, g = 0, b = 0, a = 255;
    uint32_t packed() const { return uint32_t(r) | uint32_t(g) << 8 | uint32_t(b) << 16 | uint32_t(a) << 24; }
};

// A filled rectangle (glyph < 0) or one character of the bitmap font scaled by `scale` (glyph = ASCII code).
struct Quad {
    Rect rect;
    Color color;
    int glyph = -1;
    int scale = 1;
};

class DrawList {
public:
    void clear() { quads_.clear(); }
    size_t fill(const Rect& rect, Color color);
    // Draws `text` with its top-left corner at `topLeft`; stops at maxWidth pixels when given (> 0).
    void text(glm::vec2 topLeft, std::string_view text, Color color, int scale, float maxWidth = 0.0f);
    std::vector<Quad>& quads() { return quads_; }
    const std::vector<Quad>& quads() const { return quads_; }

private:
    std::vector<Quad> quads_;
};

// One frame of input, already reduced to what widgets need.
struct Input {
    glm::vec2 mouse{-1.0f, -1.0f};
    bool mouseDown = false;     // left button held
    bool mousePressed = false;  // left button went down this frame
    bool rightPressed = false;  // right button went down this frame (resets a parameter)
    float scroll = 0.0f;        // wheel steps this frame (positive: away from the user)
    int focusMove = 0;          // keyboard: +1 next widget, -1 previous
    int adjust = 0;             // keyboard: +1 increase / next choice, -1 decrease / previous choice
    bool activate = false;      // keyboard: press the focused button / toggle the focused checkbox
};

namespace palette {
constexpr Color kPanel{18, 20, 26, 255};
constexpr Color kRow{44, 48, 60, 255};
constexpr Color kRowHover{58, 64, 80, 255};
constexpr Color kFill{62, 104, 168, 255};
constexpr Color kFocus{236, 184, 64, 255};
constexpr Color kText{232, 232, 236, 255};
constexpr Color kDim{150, 154, 166, 255};
constexpr Color kHeading{255, 204, 120, 255};
constexpr Color kError{255, 120, 110, 255};
constexpr Color kErrorBack{70, 12, 12, 235};
}  // namespace palette

enum class Edit { None, Changed, Reset };

// Slider mapping between a parameter value and the bar fraction in [0, 1]. Linear, or logarithmic for
// spec.logScale (a zero minimum maps to fraction 0 exactly; the log range then starts at logFloor(spec)).
float sliderFraction(const ParamSpec& spec, float value);
float sliderValue(const ParamSpec& spec, float fraction);
float logFloor(const ParamSpec& spec);
// One keyboard step (1% of the bar, or 1 for integer parameters) in `direction` (+1 / -1), clamped.
float sliderStep(const ParamSpec& spec, float value, int direction);
// Value text as sliders show it: choice name, integer, or 4 significant digits.
std::string formatSliderValue(const ParamSpec& spec, float value);

class Context {
public:
    void begin(const Input& input, int screenWidth, int screenHeight, int scale);
    void end();

    // A column of widgets at (x, y), widthChars characters wide and at most maxHeight tall: taller content
    // scrolls with the wheel (and follows the keyboard focus).
    void beginPanel(const std::string& id, float x, float y, int widthChars, float maxHeight);
    void endPanel();

    void heading(std::string_view text);
    // A collapsible section header ("+ text" closed, "- text" open). One section of a panel is open at a time
    // (opening one closes the others), so a panel of sections fits a small window; `openByDefault` names the
    // section open until the user picks another. Returns whether this section's widgets should follow.
    bool section(std::string_view text, bool openByDefault = false);
    // The open section of panel `panelId` ("" when all are closed or none was shown yet); setOpenSection opens one.
    std::string openSection(const std::string& panelId) const;
    void setOpenSection(const std::string& panelId, const std::string& text);
    void label(std::string_view text, Color color = palette::kDim);
    // A label wrapped over as many rows as the panel's width needs (method descriptions, file paths): a long one
    // was clipped at the panel's edge.
    void paragraph(std::string_view text, Color color = palette::kDim);
    bool button(std::string_view text);
    bool checkbox(std::string_view text, bool& value);
    // "text   < option >": a click on the left half of the value steps back, on the right half forward.
    bool selector(std::string_view text, const std::vector<std::string>& options, int& index);
    // A bar filled to the value's fraction with "text  value" on it. Enumerations (spec.choices) become
    // selectors, integers snap, logScale moves in log space. Right click: Edit::Reset (value left unchanged).
    // valueText, when given, replaces the number shown (e.g. "scene" for an override that is not set).
    Edit slider(std::string_view text, const ParamSpec& spec, float& value, const char* valueText = nullptr);

    // Drawing outside panels (stats line, error overlay).
    void box(const Rect& rect, Color color) { draw_.fill(rect, color); }
    void textAt(glm::vec2 topLeft, std::string_view text, Color color, float maxWidth = 0.0f) {
        draw_.text(topLeft, text, color, scale_, maxWidth);
    }

    bool mouseOverUi() const { return mouseOverUi_ || !active_.empty(); }
    const DrawList& drawList() const { return draw_; }
    int scale() const { return scale_; }
    float lineHeight() const;   // text height plus spacing
    float rowHeight() const;    // height of a widget row
    // Where the widget labelled `text` was laid out this frame (for tests and tools).
    std::optional<Rect> widgetRect(std::string_view text) const;
    // Every widget laid out this frame (label, rectangle), in order; the panel's visible area.
    const std::vector<std::pair<std::string, Rect>>& layout() const { return layout_; }
    std::optional<Rect> panelArea(const std::string& id) const;
    int focusIndex() const { return focus_; }

private:
    struct Panel {
        std::string id;
        Rect area;          // visible area
        float contentTop;   // y of the first row in content coordinates
        float cursor;       // y of the next row, content coordinates
        size_t backgroundQuad;
        float focusTop = -1, focusBottom = -1;
    };
    // Lays out the next row; false when it is scrolled out of view (not drawn, not hit).
    bool nextRow(float height, Rect& row);
    bool focusable(const std::string& id, bool& focused);
    std::string widgetId(std::string_view text) const;
    bool hovered(const Rect& r) const { return r.contains(input_.mouse); }

    Input input_;
    int screenWidth_ = 0, screenHeight_ = 0, scale_ = 1;
    DrawList draw_;
    std::optional<Panel> panel_;
    std::map<std::string, float> scroll_;
    std::string active_;           // widget being dragged
    bool mouseOverUi_ = false;
    int focus_ = -1, focusableCount_ = 0, lastFocusableCount_ = 0;
    std::vector<std::pair<std::string, Rect>> layout_;
    std::map<std::string, std::string> openSection_;  // panel id -> open section ("" = all closed)
    std::map<std::string, std::string> pendingSection_;  // a header clicked this frame, applied at begin()
    std::map<std::string, Rect> panelAreas_;
};

}  // namespace glimmer::ui
