#include "app/walkthrough/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ui/font.h"

namespace glimmer {

namespace {

constexpr double kMessageSeconds = 4.0;

// Three significant digits at most (the stats line lists every pass: it must fit 1280 pixels).
std::string formatMsShort(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, ms >= 100.0 ? "%.0f" : (ms >= 10.0 ? "%.1f" : "%.2f"), ms);
    return text;
}

}  // namespace

std::string twoDecimals(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", value);
    return text;
}

void Overlay::notify(const std::string& text, double now) {
    message_ = text;
    messageUntil_ = now + kMessageSeconds;
}

std::vector<StatsLine> Overlay::statsLines(const Renderer& renderer, const WindowStatus& status, float available,
                                           int uiScale) {
    std::vector<StatsLine> lines;
    std::string frame = "frame " + formatMsShort(status.frameMs) + " ms (" +
                        std::to_string(int(std::lround(1000.0 / std::max(status.frameMs, 1e-3)))) + " fps) " +
                        status.resolution;
    std::string timers = "GPU ms:";
    for (const PassTiming& t : renderer.passTimings())   // NaN: no plausible result (render/frame/pass_timer.h)
        timers += " " + t.name + " " + (std::isnan(t.gpuMs) ? std::string("n/a") : formatMsShort(t.gpuMs));
    if (renderer.passTimings().empty()) timers += " (pending)";
    if (float(ui::textWidth(frame + " | " + timers, uiScale)) <= available) {
        lines.push_back({frame + " | " + timers});
    } else {
        // Wrapped at the window's width: one pass list line was clipped ("... lightin") at 1280x720.
        size_t columns = size_t(std::max(10.0f, (available + float(uiScale)) / float(ui::kCellWidth * uiScale)));
        for (const std::string& l : ui::wrapText(frame, columns)) lines.push_back({l});
        for (const std::string& l : ui::wrapText(timers, columns)) lines.push_back({l});
    }
    char samples[32] = "";
    if (renderer.accumulating()) std::snprintf(samples, sizeof samples, " %u spp", unsigned(status.sampleIndex) + 1u);
    char where[160];
    std::snprintf(where, sizeof where, "pos %.2f %.2f %.2f  speed %.2g m/s  vsync %s  ibl %s%s%s", status.position.x,
                  status.position.y, status.position.z, double(status.moveSpeed), status.vsync ? "on" : "off",
                  renderer.settings().ibl.c_str(), samples, status.mouseCaptured ? "  mouse captured (C/Esc)" : "");
    std::string note = status.softwareRenderer ? "GPU timers unreliable on software renderers (llvmpipe)" : "";
    if (note.empty()) {
        lines.push_back({where, true});
    } else if (float(ui::textWidth(note + " | " + where, uiScale)) <= available) {
        lines.push_back({note + " | " + where, true});
    } else {
        lines.push_back({note, true});
        lines.push_back({where, true});
    }
    if (!renderer.waitingRefinements().empty()) {
        // The frames after the first picture finish what it went without, one step a frame (Renderer::RefinementPace).
        std::string refining = "refining, one a frame:";
        for (size_t i = 0; i < renderer.waitingRefinements().size(); ++i)
            refining += (i ? ", " : " ") + renderer.waitingRefinements()[i];
        lines.push_back({refining});
    }
    if (status.edited && !renderer.lastEditPasses().empty()) {
        std::string edits = "last edit:";
        for (const PassTiming& t : renderer.lastEditPasses()) edits += " " + t.name + " " + formatMsShort(t.wallMs);
        lines.push_back({edits + " ms"});
    }
    return lines;
}

void Overlay::drawErrors(ui::Context& ui, const std::vector<std::string>& errors, int width, int height,
                         float statsHeight) {
    float line = ui.lineHeight();
    float margin = overlayMargin(ui);
    size_t columns = size_t(std::max(10.0f, (float(width) - 2.0f * margin) / float(ui::kCellWidth * ui.scale())));
    std::vector<std::string> lines;
    for (const std::string& error : errors)
        for (const std::string& l : ui::wrapText(error, columns)) lines.push_back(l);
    if (lines.empty()) return;
    float boxHeight = float(lines.size()) * line + 2.0f * margin;
    float top = float(height) - statsHeight - boxHeight;
    ui.box({0.0f, top, float(width), boxHeight}, ui::palette::kErrorBack);
    for (size_t i = 0; i < lines.size(); ++i)
        ui.textAt({margin, top + margin + float(i) * line}, lines[i], ui::palette::kError);
}

void Overlay::drawStats(ui::Context& ui, const std::vector<StatsLine>& stats, int width, int height,
                        float statsHeight, double now) const {
    float line = ui.lineHeight();
    float margin = overlayMargin(ui);
    float top = float(height) - statsHeight;
    ui.box({0.0f, top, float(width), statsHeight}, {0, 0, 0, 200});
    if (now < messageUntil_) {
        // Transient notices (screenshot written, shaders rebuilt, camera) in the top-right corner, wrapped within
        // 60% of the width (a long one was clipped).
        size_t columns = size_t(std::max(10.0f, (float(width) * 0.6f - 2.0f * margin) / float(ui::kCellWidth * ui.scale())));
        std::vector<std::string> lines = ui::wrapText(message_, columns);
        float textW = 0.0f;
        for (const std::string& l : lines) textW = std::max(textW, float(ui::textWidth(l, ui.scale())));
        float boxW = textW + 2.0f * margin;
        ui.box({float(width) - boxW - margin, margin, boxW, float(lines.size()) * line + margin}, {0, 0, 0, 200});
        for (size_t i = 0; i < lines.size(); ++i)
            ui.textAt({float(width) - boxW, margin + margin * 0.5f + float(i) * line}, lines[i], ui::palette::kHeading,
                      boxW - margin);
    }
    for (size_t i = 0; i < stats.size(); ++i)
        ui.textAt({margin, top + margin + float(i) * line}, stats[i].text,
                  stats[i].dim ? ui::palette::kDim : ui::palette::kText, float(width) - 2.0f * margin);
}

}  // namespace glimmer
