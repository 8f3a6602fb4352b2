#include "app/walkthrough/input.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace glimmer {

namespace {
constexpr float kLookRadiansPerPixel = 0.0025f;
constexpr float kWheelSpeedFactor = 1.2f;
constexpr double kQuitConfirmSeconds = 3.0;
}  // namespace

WindowInput::WindowInput(GlfwWindow& window, ui::WindowControls& controls, CameraMotion& camera,
                         WindowActions& actions, const std::optional<std::string>& script)
    : window_(window), controls_(controls), camera_(camera), actions_(actions) {
    if (script) script_ = std::make_unique<ui::ScriptPlayer>(ui::readInputScript(*script));
}

void WindowInput::beginFrame(WindowEvents& events, double start, double now) {
    now_ = now;
    if (events.focusLost) keys_.releaseAll(now);
    for (const WindowEvents::KeyChange& change : events.changes) {
        if (change.down) keys_.press(change.key, change.seconds - start);
        else keys_.release(change.key, change.seconds - start);
    }
}

ui::Input WindowInput::panelInput(const WindowEvents& events, int width, int height) {
    ui::Input input = handleKeys(events, width, height);
    input.focusMove += std::exchange(pendingScriptInput_.focusMove, 0);
    input.adjust += std::exchange(pendingScriptInput_.adjust, 0);
    input.activate |= std::exchange(pendingScriptInput_.activate, false);
    return input;
}

void WindowInput::startScriptClock(double now) {
    if (script_ && scriptOffset_ < 0.0) scriptOffset_ = now;
}

std::vector<std::string> WindowInput::dueScriptScreenshots() {
    std::vector<std::string> due;
    std::vector<PendingShot> waiting;
    for (PendingShot& shot : scriptScreenshots_) {
        if (shot.framesToWait-- > 0) waiting.push_back(std::move(shot));
        else due.push_back(std::move(shot.path));
    }
    scriptScreenshots_ = std::move(waiting);
    return due;
}

bool WindowInput::panelScriptInputPending() const {
    return pendingScriptInput_.focusMove != 0 || pendingScriptInput_.adjust != 0 || pendingScriptInput_.activate;
}

bool WindowInput::shiftHeld() const { return keys_.down(GLFW_KEY_LEFT_SHIFT) || keys_.down(GLFW_KEY_RIGHT_SHIFT); }

double WindowInput::heldSeconds(ui::MoveKey key, double from, double to) const {
    auto held = [&](int k) { return keys_.heldSeconds(k, from, to); };
    switch (key) {
    case ui::MoveKey::Forward: return held(GLFW_KEY_W);
    case ui::MoveKey::Back: return held(GLFW_KEY_S);
    case ui::MoveKey::Left: return held(GLFW_KEY_A);
    case ui::MoveKey::Right: return held(GLFW_KEY_D);
    case ui::MoveKey::Up: return held(GLFW_KEY_E);
    case ui::MoveKey::Down: return held(GLFW_KEY_Q);
    case ui::MoveKey::Fast: return std::min(to - from, held(GLFW_KEY_LEFT_SHIFT) + held(GLFW_KEY_RIGHT_SHIFT));
    }
    return 0.0;
}

void WindowInput::setCaptured(bool captured) {
    captured_ = captured;
    window_.setCursorCaptured(captured_ || rightLook_);
    lookStarted_ = false;
}

ui::Input WindowInput::handleKeys(const WindowEvents& events, int width, int height) {
    ui::Input input;
    GLFWwindow* w = window_.glfwHandle();
    for (const WindowEvents::Key& key : events.keys) {
        bool shift = key.mods & GLFW_MOD_SHIFT;
        // Arrows repeat while held (panel navigation); other keys act once per press.
        switch (key.key) {
        case GLFW_KEY_UP: input.focusMove -= 1; continue;
        case GLFW_KEY_DOWN: input.focusMove += 1; continue;
        case GLFW_KEY_LEFT: input.adjust -= 1; continue;
        case GLFW_KEY_RIGHT: input.adjust += 1; continue;
        default: break;
        }
        if (key.repeat) continue;
        switch (key.key) {
        case GLFW_KEY_ENTER:
        case GLFW_KEY_KP_ENTER: input.activate = true; break;
        case GLFW_KEY_ESCAPE:
            // Esc releases the mouse; otherwise it quits only when pressed twice within kQuitConfirmSeconds, so a
            // stray press does not end a session.
            if (captured_) {
                setCaptured(false);
            } else if (now_ - escapeAt_ <= kQuitConfirmSeconds) {
                window_.requestClose();
            } else {
                escapeAt_ = now_;
                actions_.showMessage("press Esc again to quit");
            }
            break;
        case GLFW_KEY_F5: actions_.reloadAllShaders(); break;
        case GLFW_KEY_F12: actions_.requestScreenshot(shift); break;
        case GLFW_KEY_H: actions_.toggleUi(); break;
        case GLFW_KEY_C: setCaptured(!captured_); break;
        case GLFW_KEY_V:
            controls_.vsync = !controls_.vsync;
            window_.setVsync(controls_.vsync);
            break;
        case GLFW_KEY_P: camera_.togglePathPlaying(); break;
        case GLFW_KEY_F: camera_.toggleWalking(); break;
        case GLFW_KEY_R: actions_.toggleRecording(); break;
        case GLFW_KEY_M: actions_.cycleMethod(shift ? -1 : 1); break;
        case GLFW_KEY_N: actions_.cycleDebugView(shift ? -1 : 1); break;
        case GLFW_KEY_B: actions_.toggleSplit(shift); break;
        case GLFW_KEY_I: actions_.cycleIblMode(shift ? -1 : 1); break;
        default:
            if (key.key >= GLFW_KEY_1 && key.key <= GLFW_KEY_9) camera_.jumpToCamera(key.key - GLFW_KEY_1);
            break;
        }
    }
    // Mouse in framebuffer pixels (the window size differs from the framebuffer on scaled displays).
    double cx = 0, cy = 0;
    window_.cursorPosition(cx, cy);
    int ww = 1, wh = 1;
    window_.windowSize(ww, wh);
    bool looking = captured_ || rightLook_;
    if (!looking) {
        input.mouse = {float(cx * width / std::max(ww, 1)), float(cy * height / std::max(wh, 1))};
        input.mouseDown = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        input.mousePressed = events.leftPressed;
        input.rightPressed = events.rightPressed;
        input.scroll = float(events.scrollY);
        actions_.dragDivider(input, events.leftPressed, width);
    }
    return input;
}

// One input-script event at frame-clock time `t`: keys go through the same paths as the window's.
void WindowInput::applyScriptEvent(const ui::ScriptEvent& e, double t, int width, int height) {
    auto action = [&](int key) {
        now_ = t;   // a scripted key acts at its own time (Esc's confirmation window)
        WindowEvents single;
        single.keys.push_back({key, shiftHeld() ? GLFW_MOD_SHIFT : 0, false});
        ui::Input input = handleKeys(single, width, height);
        pendingScriptInput_.focusMove += input.focusMove;
        pendingScriptInput_.adjust += input.adjust;
        pendingScriptInput_.activate |= input.activate;
    };
    switch (e.kind) {
    case ui::ScriptEvent::Kind::Down:
        keys_.press(e.key, t);
        action(e.key);
        break;
    case ui::ScriptEvent::Kind::Up: keys_.release(e.key, t); break;
    case ui::ScriptEvent::Kind::Press:
        keys_.press(e.key, t);
        keys_.release(e.key, t);
        action(e.key);
        break;
    case ui::ScriptEvent::Kind::Look:
        camera_.turn(e.dx * kLookRadiansPerPixel, -e.dy * kLookRadiansPerPixel);
        break;
    case ui::ScriptEvent::Kind::Print: {
        const glm::vec3& p = camera_.camera().position;
        std::printf("time %.3f position %.4f %.4f %.4f mode %s speed %.4f\n", e.seconds, p.x, p.y, p.z,
                    camera_.mode() == ui::MoveMode::Walk ? "walk" : "fly", double(controls_.moveSpeed));
        std::fflush(stdout);
        break;
    }
    case ui::ScriptEvent::Kind::Screenshot:
        scriptScreenshots_.push_back({e.path, 1});
        break;
    case ui::ScriptEvent::Kind::Quit: scriptQuit_ = true; break;
    }
}

void WindowInput::moveCamera(const WindowEvents& events, double from, double to, int width, int height) {
    GLFWwindow* w = window_.glfwHandle();
    // Right button held outside the panel: mouse look (the cursor is hidden while it is held).
    bool rightDown = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (events.rightPressed && !actions_.pointerOverUi() && !rightLook_) {
        rightLook_ = true;
        window_.setCursorCaptured(true);
        lookStarted_ = false;
    }
    if (rightLook_ && !rightDown) {
        rightLook_ = false;
        window_.setCursorCaptured(captured_);
    }
    double cx = 0, cy = 0;
    window_.cursorPosition(cx, cy);
    if (captured_ || rightLook_) {
        if (lookStarted_ && (cx != lastCursor_.x || cy != lastCursor_.y)) {
            camera_.turn(float(cx - lastCursor_.x) * kLookRadiansPerPixel,
                         -float(cy - lastCursor_.y) * kLookRadiansPerPixel);
            camera_.stopPathPlaying();
        }
        lookStarted_ = true;
    }
    lastCursor_ = {cx, cy};

    if (events.scrollY != 0.0 && !actions_.pointerOverUi()) {
        ParamSpec speed = ui::moveSpeedSpec();
        controls_.moveSpeed = std::clamp(controls_.moveSpeed * std::pow(kWheelSpeedFactor, float(events.scrollY)),
                                         speed.minValue, speed.maxValue);
    }
    // Script events apply at their own times, with the motion advanced exactly up to each one. At most one panel
    // key per frame: the panel folds a frame's keys into one input (moves summed, then activate), so "enter, up"
    // in one long frame would act as "up, enter"; the rest waits for the next frame, in order.
    auto held = [&](ui::MoveKey key, double a, double b) { return heldSeconds(key, a, b); };
    double at = from;
    if (script_ && scriptOffset_ >= 0.0)
        while (!panelScriptInputPending()) {
            const ui::ScriptEvent* e = script_->nextDue(to - scriptOffset_);
            if (!e) break;
            double t = std::max(at, e->seconds + scriptOffset_);
            camera_.advance(held, at, t);
            at = t;
            applyScriptEvent(*e, t, width, height);
        }
    camera_.advance(held, at, to);
    keys_.forgetBefore(to);
}

}  // namespace glimmer
