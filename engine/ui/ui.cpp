#include "ui/ui.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/font.h"

namespace glimmer::ui {

size_t DrawList::fill(const Rect& rect, Color color) {
    quads_.push_back({rect, color, -1, 1});
    return quads_.size() - 1;
}

void DrawList::text(glm::vec2 topLeft, std::string_view text, Color color, int scale, float maxWidth) {
    // Glyphs start on whole pixels: at a fractional origin the nearest-texel font lookup would drop or double
    // columns ("ertrance" for "entrance").
    topLeft = glm::floor(topLeft);
    for (size_t i = 0; i < text.size(); ++i) {
        float x = topLeft.x + float(i * kCellWidth * scale);
        if (maxWidth > 0.0f && x + float(kGlyphWidth * scale) > topLeft.x + maxWidth) break;
        if (text[i] == ' ') continue;
        quads_.push_back({{x, topLeft.y, float(kGlyphWidth * scale), float(kCellHeight * scale)}, color,
                          static_cast<unsigned char>(text[i]), scale});
    }
}

// ---- slider mapping ----

float logFloor(const ParamSpec& spec) {
    return spec.minValue > 0.0f ? spec.minValue : std::min(1e-3f, spec.maxValue * 1e-6f);
}

static bool usesLog(const ParamSpec& spec) { return spec.logScale && spec.maxValue > 0.0f; }

float sliderFraction(const ParamSpec& spec, float value) {
    if (spec.maxValue <= spec.minValue) return 0.0f;
    float t;
    if (usesLog(spec)) {
        float lo = logFloor(spec);
        t = value <= lo ? 0.0f : std::log(value / lo) / std::log(spec.maxValue / lo);
    } else {
        t = (value - spec.minValue) / (spec.maxValue - spec.minValue);
    }
    return std::clamp(t, 0.0f, 1.0f);
}

float sliderValue(const ParamSpec& spec, float fraction) {
    float t = std::clamp(fraction, 0.0f, 1.0f);
    float value;
    if (usesLog(spec)) {
        float lo = logFloor(spec);
        value = t <= 0.0f ? spec.minValue : lo * std::exp(t * std::log(spec.maxValue / lo));
    } else {
        value = spec.minValue + t * (spec.maxValue - spec.minValue);
    }
    if (spec.integer || !spec.choices.empty()) value = std::round(value);
    return std::clamp(value, spec.minValue, spec.maxValue);
}

float sliderStep(const ParamSpec& spec, float value, int direction) {
    if (direction == 0) return value;
    if (spec.integer || !spec.choices.empty())
        return std::clamp(std::round(value) + float(direction), spec.minValue, spec.maxValue);
    float t = sliderFraction(spec, value) + 0.01f * float(direction);
    return sliderValue(spec, t);
}

std::string formatSliderValue(const ParamSpec& spec, float value) {
    int index = int(std::lround(value));
    if (!spec.choices.empty() && index >= 0 && index < int(spec.choices.size())) return spec.choices[size_t(index)];
    char text[32];
    if (spec.integer) std::snprintf(text, sizeof text, "%d", index);
    else std::snprintf(text, sizeof text, "%.4g", double(value));
    return text;
}

// ---- context ----

float Context::lineHeight() const { return float((kCellHeight + 2) * scale_); }
float Context::rowHeight() const { return float((kCellHeight + 3) * scale_); }
// Top of text centred in a widget row.
static float textTop(const Rect& row, int scale) { return std::floor(row.y + (row.h - float(kCellHeight * scale)) * 0.5f); }

void Context::begin(const Input& input, int screenWidth, int screenHeight, int scale) {
    input_ = input;
    input_.mouseDown = input.mouseDown || input.mousePressed;  // a click shorter than a frame still counts
    screenWidth_ = screenWidth;
    screenHeight_ = screenHeight;
    scale_ = std::max(1, scale);
    draw_.clear();
    layout_.clear();
    panelAreas_.clear();
    mouseOverUi_ = false;
    if (!input_.mouseDown) active_.clear();
    for (const auto& [panel, section] : pendingSection_) openSection_[panel] = section;
    pendingSection_.clear();
    lastFocusableCount_ = focusableCount_;
    focusableCount_ = 0;
    if (input_.focusMove != 0 && lastFocusableCount_ > 0) {
        // From "no focus", Down lands on the first widget and Up on the last (several presses in one frame add).
        int from = focus_ >= 0 ? focus_ : (input_.focusMove > 0 ? -1 : 0);
        focus_ = ((from + input_.focusMove) % lastFocusableCount_ + lastFocusableCount_) % lastFocusableCount_;
    }
}

void Context::end() {
    if (focus_ >= focusableCount_) focus_ = focusableCount_ > 0 ? focusableCount_ - 1 : -1;
}

void Context::beginPanel(const std::string& id, float x, float y, int widthChars, float maxHeight) {
    float pad = float(4 * scale_);
    float width = float(widthChars * kCellWidth * scale_) + 2.0f * pad;
    Panel panel{id, {x, y, width, maxHeight}, y + pad, y + pad, draw_.fill({x, y, width, 0.0f}, palette::kPanel)};
    panel_ = panel;
}

void Context::endPanel() {
    if (!panel_) return;
    Panel& p = *panel_;
    float pad = float(4 * scale_);
    float contentHeight = p.cursor - p.contentTop + 2.0f * pad;
    float visible = std::min(contentHeight, p.area.h);
    float maxScroll = std::max(0.0f, contentHeight - p.area.h);
    float& scroll = scroll_[p.id];
    Rect background{p.area.x, p.area.y, p.area.w, visible};
    if (background.contains(input_.mouse)) {
        mouseOverUi_ = true;
        scroll -= input_.scroll * 3.0f * rowHeight();
    }
    // Keep the keyboard focus in view.
    if (input_.focusMove != 0 && p.focusTop >= 0.0f) {
        float top = p.focusTop - p.contentTop, bottom = p.focusBottom - p.contentTop + 2.0f * pad;
        if (top < scroll) scroll = top;
        if (bottom > scroll + p.area.h) scroll = bottom - p.area.h;
    }
    scroll = std::clamp(scroll, 0.0f, maxScroll);
    draw_.quads()[p.backgroundQuad].rect = background;
    // Content taller than the panel: a scroll bar in the right padding says that the wheel scrolls, and how far.
    if (maxScroll > 0.0f) {
        float barX = p.area.x + p.area.w - pad + float(scale_), barW = float(2 * scale_);
        draw_.fill({barX, p.area.y, barW, visible}, palette::kRow);
        float thumbH = std::max(float(8 * scale_), visible * visible / contentHeight);
        float thumbY = p.area.y + (visible - thumbH) * (scroll / maxScroll);
        draw_.fill({barX, thumbY, barW, thumbH}, palette::kDim);
    }
    panelAreas_[p.id] = background;
    panel_.reset();
}

bool Context::nextRow(float height, Rect& row) {
    Panel& p = *panel_;
    float pad = float(4 * scale_);
    float scroll = scroll_.count(p.id) ? scroll_.at(p.id) : 0.0f;
    row = {p.area.x + pad, p.area.y + pad + (p.cursor - p.contentTop) - scroll, p.area.w - 2.0f * pad, height};
    p.cursor += height + float(scale_);
    return row.y >= p.area.y && row.y + row.h <= p.area.y + p.area.h;
}

std::string Context::widgetId(std::string_view text) const {
    return (panel_ ? panel_->id : std::string()) + "/" + std::string(text);
}

bool Context::focusable(const std::string&, bool& focused) {
    int index = focusableCount_++;
    focused = index == focus_;
    return focused;
}

std::optional<Rect> Context::widgetRect(std::string_view text) const {
    for (auto it = layout_.rbegin(); it != layout_.rend(); ++it)
        if (it->first == text) return it->second;
    return std::nullopt;
}

namespace {
void outline(DrawList& draw, const Rect& r, Color color, float t) {
    draw.fill({r.x, r.y, r.w, t}, color);
    draw.fill({r.x, r.y + r.h - t, r.w, t}, color);
    draw.fill({r.x, r.y, t, r.h}, color);
    draw.fill({r.x + r.w - t, r.y, t, r.h}, color);
}
}  // namespace

void Context::heading(std::string_view text) {
    if (!panel_) return;
    Rect row;
    panel_->cursor += float(2 * scale_);
    if (nextRow(lineHeight(), row)) draw_.text({row.x, row.y + float(scale_)}, text, palette::kHeading, scale_, row.w);
    layout_.emplace_back(std::string(text), row);
}

std::optional<Rect> Context::panelArea(const std::string& id) const {
    auto it = panelAreas_.find(id);
    if (it == panelAreas_.end()) return std::nullopt;
    return it->second;
}

std::string Context::openSection(const std::string& panelId) const {
    auto it = openSection_.find(panelId);
    return it == openSection_.end() ? std::string() : it->second;
}

void Context::setOpenSection(const std::string& panelId, const std::string& text) { openSection_[panelId] = text; }

bool Context::section(std::string_view text, bool openByDefault) {
    if (!panel_) return false;
    std::string name(text);
    auto state = openSection_.find(panel_->id);
    if (state == openSection_.end() && openByDefault) state = openSection_.emplace(panel_->id, name).first;
    bool open = state != openSection_.end() && state->second == name;
    std::string shown = (open ? "- " : "+ ") + name;
    Rect row;
    float contentY = panel_->cursor;
    panel_->cursor += float(scale_);
    bool visible = nextRow(rowHeight(), row);
    layout_.emplace_back(shown, row);
    bool focused;
    focusable(widgetId(text), focused);
    int index = focusableCount_ - 1;
    bool toggled = false;
    if (visible && input_.mousePressed && hovered(row)) { toggled = true; focus_ = index; focused = true; }
    if (focused && input_.activate) toggled = true;
    if (focused) { panel_->focusTop = contentY; panel_->focusBottom = contentY + row.h; }
    // Applied at the next begin(): sections above this one were laid out already this frame, and opening this
    // one now would show two open sections (too tall for the window) for a frame.
    if (toggled) pendingSection_[panel_->id] = open ? std::string() : name;
    if (visible) {
        draw_.fill(row, hovered(row) ? palette::kRowHover : palette::kPanel);
        draw_.text({row.x + float(2 * scale_), textTop(row, scale_)}, shown, palette::kHeading, scale_, row.w);
        if (focused) outline(draw_, row, palette::kFocus, float(scale_));
    }
    return open;
}

void Context::label(std::string_view text, Color color) {
    if (!panel_) return;
    Rect row;
    if (nextRow(lineHeight(), row)) draw_.text({row.x, row.y + float(scale_)}, text, color, scale_, row.w);
    layout_.emplace_back(std::string(text), row);
}

void Context::paragraph(std::string_view text, Color color) {
    if (!panel_) return;
    float width = panel_->area.w - float(8 * scale_);
    size_t columns = size_t(std::max(1.0f, (width + float(scale_)) / float(kCellWidth * scale_)));
    for (const std::string& line : wrapText(std::string(text), columns)) label(line, color);
}

bool Context::button(std::string_view text) {
    if (!panel_) return false;
    Rect row;
    float contentY = panel_->cursor;
    bool visible = nextRow(rowHeight(), row);
    layout_.emplace_back(std::string(text), row);
    bool focused;
    focusable(widgetId(text), focused);
    int index = focusableCount_ - 1;
    bool pressed = false;
    if (visible && input_.mousePressed && hovered(row)) { pressed = true; focus_ = index; focused = true; }
    if (focused && input_.activate) pressed = true;
    if (focused) { panel_->focusTop = contentY; panel_->focusBottom = contentY + row.h; }
    if (visible) {
        draw_.fill(row, hovered(row) ? palette::kRowHover : palette::kRow);
        float textX = row.x + std::max(0.0f, (row.w - float(textWidth(text, scale_))) * 0.5f);
        draw_.text({textX, textTop(row, scale_)}, text, palette::kText, scale_, row.w);
        if (focused) outline(draw_, row, palette::kFocus, float(scale_));
    }
    return pressed;
}

bool Context::checkbox(std::string_view text, bool& value) {
    if (!panel_) return false;
    Rect row;
    float contentY = panel_->cursor;
    bool visible = nextRow(rowHeight(), row);
    layout_.emplace_back(std::string(text), row);
    bool focused;
    focusable(widgetId(text), focused);
    int index = focusableCount_ - 1;
    bool toggled = false;
    if (visible && input_.mousePressed && hovered(row)) { toggled = true; focus_ = index; focused = true; }
    if (focused && (input_.activate || input_.adjust != 0)) toggled = true;
    if (toggled) value = !value;
    if (focused) { panel_->focusTop = contentY; panel_->focusBottom = contentY + row.h; }
    if (visible) {
        draw_.fill(row, hovered(row) ? palette::kRowHover : palette::kRow);
        float box = float((kCellHeight - 1) * scale_);
        Rect square{row.x + float(2 * scale_), row.y + (row.h - box) * 0.5f, box, box};
        outline(draw_, square, palette::kText, float(scale_));
        if (value) draw_.fill({square.x + 2.0f * scale_, square.y + 2.0f * scale_, box - 4.0f * scale_,
                               box - 4.0f * scale_}, palette::kFill);
        draw_.text({square.x + box + float(4 * scale_), textTop(row, scale_)}, text, palette::kText, scale_);
        if (focused) outline(draw_, row, palette::kFocus, float(scale_));
    }
    return toggled;
}

bool Context::selector(std::string_view text, const std::vector<std::string>& options, int& index) {
    ParamSpec spec;
    spec.name = std::string(text);
    spec.choices = options;
    spec.maxValue = float(std::max<size_t>(options.size(), 1) - 1);
    float value = float(index);
    Edit edit = slider(text, spec, value);
    if (edit == Edit::Changed) index = int(value);
    return edit == Edit::Changed;
}

Edit Context::slider(std::string_view text, const ParamSpec& spec, float& value, const char* valueText) {
    if (!panel_) return Edit::None;
    Rect row;
    float contentY = panel_->cursor;
    bool visible = nextRow(rowHeight(), row);
    layout_.emplace_back(std::string(text), row);
    std::string id = widgetId(text);
    bool focused;
    focusable(id, focused);
    int index = focusableCount_ - 1;
    if (focused) { panel_->focusTop = contentY; panel_->focusBottom = contentY + row.h; }
    bool choice = !spec.choices.empty();
    int choiceCount = int(spec.choices.size());
    // Selectors show "text" on the left and "< choice >" in the value area on the right.
    Rect valueArea = row;
    if (choice) {
        valueArea.w = std::round(row.w * 0.55f);
        // A label longer than the remaining 45% ("angular_covariance" was cut to "angular_covaria") takes room from
        // the value area, down to what the longest choice and the arrows need.
        float labelRoom = row.w - valueArea.w - float(4 * scale_);
        if (float(textWidth(text, scale_)) > labelRoom) {
            size_t longest = 0;
            for (const std::string& c : spec.choices) longest = std::max(longest, c.size());
            float needed = float((int(longest) + 2) * kCellWidth * scale_ + 2 * scale_);
            valueArea.w = std::round(std::max(needed, std::min(valueArea.w, row.w - float(textWidth(text, scale_)) -
                                                                                  float(6 * scale_))));
        }
        // A choice longer than the value area (a user method's name) takes room from a short label.
        int shownIndex = std::clamp(int(std::lround(value)), 0, std::max(choiceCount - 1, 0));
        float shownWidth = choiceCount > 0 ? float(textWidth(spec.choices[size_t(shownIndex)], scale_)) : 0.0f;
        float cellWidth = float(kCellWidth * scale_);
        if (shownWidth + 2.0f * cellWidth + float(2 * scale_) > valueArea.w)
            valueArea.w = std::round(std::max(valueArea.w, std::min(shownWidth + 2.0f * cellWidth + float(2 * scale_),
                                                                     row.w - float(textWidth(text, scale_)) -
                                                                         float(6 * scale_))));
        valueArea.x = row.x + row.w - valueArea.w;
    }

    Edit edit = Edit::None;
    float newValue = value;
    if (visible && input_.rightPressed && hovered(row)) {
        focus_ = index;
        edit = Edit::Reset;
    }
    if (visible && input_.mousePressed && hovered(row)) {
        focus_ = index;
        focused = true;
        if (choice) {
            // A click steps: left half of the value area back, anywhere else forward.
            int step = (valueArea.contains(input_.mouse) && input_.mouse.x < valueArea.x + valueArea.w * 0.5f) ? -1 : 1;
            newValue = float(((int(std::lround(value)) + step) % choiceCount + choiceCount) % choiceCount);
        } else {
            active_ = id;
        }
    }
    if (!choice && active_ == id && input_.mouseDown)
        newValue = sliderValue(spec, (input_.mouse.x - row.x) / row.w);
    if (focused && input_.adjust != 0) {
        if (choice)
            newValue = float(((int(std::lround(value)) + input_.adjust) % choiceCount + choiceCount) % choiceCount);
        else
            newValue = sliderStep(spec, value, input_.adjust);
    }
    if (edit == Edit::None && newValue != value) {
        value = newValue;
        edit = Edit::Changed;
    }

    if (visible) {
        bool hot = hovered(row) || active_ == id;
        draw_.fill(row, hot ? palette::kRowHover : palette::kRow);
        float textY = textTop(row, scale_);
        std::string shown = valueText ? std::string(valueText) : formatSliderValue(spec, value);
        if (choice) {
            draw_.text({row.x + float(2 * scale_), textY}, text, palette::kText, scale_, row.w - valueArea.w);
            draw_.fill(valueArea, palette::kFill);
            float cell = float(kCellWidth * scale_);
            draw_.text({valueArea.x + float(scale_), textY}, "<", palette::kText, scale_);
            draw_.text({valueArea.x + valueArea.w - cell, textY}, ">", palette::kText, scale_);
            float inner = valueArea.w - 2.0f * cell;
            float textX = valueArea.x + cell + std::max(0.0f, (inner - float(textWidth(shown, scale_))) * 0.5f);
            draw_.text({textX, textY}, shown, palette::kText, scale_, inner);
        } else {
            // No fill for a value that is not ours to show (valueText, e.g. "scene").
            if (!valueText) draw_.fill({row.x, row.y, std::round(row.w * sliderFraction(spec, value)), row.h}, palette::kFill);
            float valueWidth = float(textWidth(shown, scale_));
            draw_.text({row.x + float(2 * scale_), textY}, text, palette::kText, scale_,
                       row.w - valueWidth - float(8 * scale_));
            draw_.text({row.x + row.w - valueWidth - float(2 * scale_), textY}, shown, palette::kText, scale_);
        }
        if (focused) outline(draw_, row, palette::kFocus, float(scale_));
    }
    return edit;
}

}  // namespace glimmer::ui
