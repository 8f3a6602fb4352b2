#include "app/walkthrough/split_view.h"

#include <algorithm>
#include <cmath>

#include "glints/methods.h"
#include "ui/font.h"

namespace glimmer {

namespace {
constexpr float kDividerGrabPixels = 6.0f;
}

SplitView::SplitView(const std::optional<std::string>& method, float position) {
    if (!method) return;
    method_ = findGlintMethod(*method).id;
    fraction_ = std::clamp(position, 0.0f, 1.0f);
    enabled_ = true;
}

std::string SplitView::rightMethod(const std::string& leftMethod) const {
    if (!method_.empty()) return method_;
    for (const GlintMethod& m : glintMethods())
        if (m.id != leftMethod) return m.id;
    return leftMethod;
}

void SplitView::cycleMethod(const std::string& leftMethod) {
    const auto& methods = glintMethods();
    int n = int(methods.size()), current = 0;
    for (int i = 0; i < n; ++i)
        if (methods[size_t(i)].id == rightMethod(leftMethod)) current = i;
    method_ = methods[size_t((current + 1) % n)].id;
    enabled_ = true;
}

void SplitView::renameMethod(const std::string& from, const std::string& to) {
    if (method_ == from) method_ = to;
}

void SplitView::dragDivider(ui::Input& input, bool leftPressed, bool pointerOverUi, int width) {
    float dividerX = fraction_ * float(width);
    if (enabled_ && leftPressed && std::abs(input.mouse.x - dividerX) <= kDividerGrabPixels && !pointerOverUi)
        dragging_ = true;
    if (!input.mouseDown) dragging_ = false;
    if (dragging_) {
        fraction_ = std::clamp(input.mouse.x / float(std::max(width, 1)), 0.0f, 1.0f);
        input.mousePressed = input.mouseDown = false;
    }
}

std::optional<std::string> SplitView::render(Renderer& left, const FrameDriver& frames,
                                             WindowResolution& resolution, GLuint target, const Scene& scene,
                                             const GpuScene& gpuScene, const Camera& camera, int width, int height) {
    RenderSettings settings = left.settings();
    settings.method = rightMethod(left.settings().method);
    try {
        if (!renderer_) {
            renderer_ = std::make_unique<Renderer>(left.shaderRoot(), settings, left);   // left's probes, environment
            renderer_->setAsyncGpuTimers(true);
        }
        renderer_->setSettings(settings);
    } catch (const std::exception& e) {
        enabled_ = false;
        return "split method " + settings.method + ": " + e.what();
    }
    int renderW = width, renderH = height;
    resolution.internalSize(width, height, renderW, renderH);
    frames.renderAlongside(*renderer_, scene, gpuScene, camera, width, height, renderW, renderH);
    int x = std::clamp(int(std::lround(fraction_ * float(width))), 0, width);
    resolution.present(*renderer_, target, width, height, x);
    const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glEnable(GL_SCISSOR_TEST);
    glScissor(std::max(x - 1, 0), 0, 2, height);
    glClearNamedFramebufferfv(target, GL_COLOR, 0, white);
    glDisable(GL_SCISSOR_TEST);
    return std::nullopt;
}

void SplitView::drawLabels(ui::Context& ui, const std::string& leftMethod, int width, float margin, float line) const {
    float dividerX = fraction_ * float(width);
    std::string left = leftMethod, right = rightMethod(leftMethod);
    float leftW = float(ui::textWidth(left, ui.scale())), rightW = float(ui::textWidth(right, ui.scale()));
    ui.box({dividerX - leftW - 2.0f * margin, margin, leftW + margin, line + margin}, {0, 0, 0, 200});
    ui.textAt({dividerX - leftW - 1.5f * margin, margin * 1.5f}, left, ui::palette::kHeading);
    ui.box({dividerX + margin, margin, rightW + margin, line + margin}, {0, 0, 0, 200});
    ui.textAt({dividerX + 1.5f * margin, margin * 1.5f}, right, ui::palette::kHeading);
}

}  // namespace glimmer
