#include "app/walkthrough/loading_screen.h"

#include <glad/gl.h>
#include <GLFW/glfw3.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/image_io.h"
#include "core/log.h"
#include "ui/font.h"
#include "ui/ui.h"

namespace glimmer {

namespace {

// What the player reads for each step.
constexpr const char* kStepLabels[LoadingScreen::kStepCount] = {
    "building the shaders",
    "building the walking collision mesh",
    "environment maps (disk cache, else a preview)",
    "reflection probes (disk cache, else after the first picture)",
    "glint data",
    "ambient occlusion (disk cache, else baked)",
    "the first picture",
};

std::string seconds(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f s", ms / 1000.0);
    return text;
}

}  // namespace

double processAgeSeconds() {
    // Field 22 of /proc/self/stat: the start time in clock ticks after boot; /proc/uptime: seconds after boot.
    std::ifstream stat("/proc/self/stat"), uptime("/proc/uptime");
    std::string line;
    double up = 0.0;
    if (!std::getline(stat, line) || !(uptime >> up)) return 0.0;
    const size_t close = line.rfind(')');   // the command name may hold spaces
    if (close == std::string::npos) return 0.0;
    std::istringstream fields(line.substr(close + 2));
    std::string field;
    for (int i = 3; i <= 22 && fields >> field; ++i)
        if (i == 22) return std::max(0.0, up - double(std::strtoull(field.c_str(), nullptr, 10)) / double(sysconf(_SC_CLK_TCK)));
    return 0.0;
}

LoadingScreen::LoadingScreen(GlfwWindow& window, std::string sceneName)
    : window_(window), sceneName_(std::move(sceneName)), windowOpenedAt_(processAgeSeconds()) {
    if (const char* dir = std::getenv("GLIMMER_LOADING_SCREENSHOTS"); dir && *dir) screenshotDir_ = dir;
}

std::optional<LoadingScreen::Step> LoadingScreen::stepOfPass(const std::string& passName) {
    if (passName == "probes") return Probes;
    if (passName == "environment_glints") return GlintData;
    if (passName == "gtao") return AmbientOcclusion;
    if (passName == "lighting") return FirstPicture;   // the method's passes (their tables) prepare after it
    return std::nullopt;
}

void LoadingScreen::show(Step step, ui::UiRenderer& ui) {
    if (finished_ || int(step) <= current_) return;
    const double now = sinceWindow_.elapsedMs();
    while (int(stepStartMs_.size()) <= int(step)) stepStartMs_.push_back(now);   // skipped steps took no time
    if (current_ >= 0) log::info("view: loading: ", kStepLabels[current_], " ", seconds(now - stepStartMs_[size_t(current_)]));
    current_ = int(step);
    draw(ui);
    if (firstFrameAt_ < 0.0) {
        firstFrameAt_ = processAgeSeconds();
        log::info("view: loading frame at ", seconds(firstFrameAt_ * 1e3), " after process start (",
                  seconds(now), " after the window opened at ", seconds(windowOpenedAt_ * 1e3), ")");
    }
    glfwPollEvents();   // keep the window responsive to the window system while the next step runs
}

void LoadingScreen::draw(ui::UiRenderer& uiRenderer) {
    int width = 0, height = 0;
    window_.framebufferSize(width, height);
    if (width <= 0 || height <= 0) return;
    const int scale = std::clamp(height / 300, 1, 4);   // 2 at 720 lines: the longest step line fits 1280 x 720
    const float line = float((ui::kCellHeight + 4) * scale);
    ui::DrawList list;
    const float left = float(width) * 0.12f, top = float(height) * 0.2f, barWidth = float(width) * 0.76f;
    list.text({left, top}, "Glimmer - loading " + sceneName_, ui::palette::kHeading, scale + 1);
    float y = top + 2.5f * line;
    const double now = sinceWindow_.elapsedMs();
    for (int i = 0; i < kStepCount; ++i, y += line) {
        if (i < current_) {
            const double ms = stepStartMs_[size_t(i) + 1] - stepStartMs_[size_t(i)];
            list.text({left, y}, std::string("  done  ") + kStepLabels[i] + "  " + seconds(ms), ui::palette::kDim, scale);
        } else if (i == current_) {
            list.text({left, y}, std::string("  now   ") + kStepLabels[i] + " ...", ui::palette::kText, scale);
        } else {
            list.text({left, y}, std::string("        ") + kStepLabels[i], ui::Color{90, 94, 106, 255}, scale);
        }
    }
    y += line;
    // Progress: the steps done (a step's own progress is not known before it ends).
    const float fraction = float(std::max(current_, 0)) / float(kStepCount);
    list.fill({left, y, barWidth, line}, ui::palette::kRow);
    list.fill({left, y, barWidth * fraction, line}, ui::palette::kFill);
    list.text({left, y + 2.0f * line}, "step " + std::to_string(current_ + 1) + " of " + std::to_string(kStepCount) +
                                           ", " + seconds(now) + " since the window opened",
              ui::palette::kDim, scale);

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const float background[4] = {28.0f / 255.0f, 32.0f / 255.0f, 44.0f / 255.0f, 1.0f};
    glClearNamedFramebufferfv(0, GL_COLOR, 0, background);
    uiRenderer.draw(list, width, height);
    if (screenshotDir_) {
        std::vector<uint8_t> pixels(size_t(width) * size_t(height) * 4);
        glReadBuffer(GL_BACK);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
        char name[32];
        std::snprintf(name, sizeof name, "loading-%02d.png", framesDrawn_);
        std::filesystem::create_directories(*screenshotDir_);
        writePng(*screenshotDir_ / name, pixels.data(), width, height);
    }
    window_.swapBuffers();
    ++framesDrawn_;
}

void LoadingScreen::finish() {
    if (finished_) return;
    finished_ = true;
    const double now = sinceWindow_.elapsedMs();
    if (current_ >= 0) log::info("view: loading: ", kStepLabels[current_], " ", seconds(now - stepStartMs_[size_t(current_)]));
    log::info("view: first picture at ", seconds(processAgeSeconds() * 1e3), " after process start (", seconds(now),
              " after the window opened; ", framesDrawn_, " loading frames)");
}

}  // namespace glimmer
