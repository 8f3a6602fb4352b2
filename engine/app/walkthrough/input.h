// The window's input: keys (held keys move the camera by the time they are held, other keys act once per press),
// the mouse (look around, the panel, the split divider) and input scripts (timed events replayed as if typed,
// ui/input_script.h), which go through the same paths as the window's own events.
#pragma once
#include <glm/glm.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/walkthrough/camera_motion.h"
#include "platform/glfw_window.h"
#include "ui/input_script.h"
#include "ui/key_holds.h"
#include "ui/settings_panel.h"
#include "ui/ui.h"

namespace glimmer {

// What keys and the mouse ask of the rest of the window.
class WindowActions {
public:
    virtual ~WindowActions() = default;
    virtual void reloadAllShaders() = 0;                  // F5
    virtual void requestScreenshot(bool hdr) = 0;         // F12 (PNG), Shift+F12 (EXR)
    virtual void toggleUi() = 0;                          // H
    virtual void toggleRecording() = 0;                   // R
    virtual void cycleMethod(int step) = 0;               // M, Shift+M
    virtual void cycleDebugView(int step) = 0;            // N, Shift+N
    virtual void toggleSplit(bool nextMethod) = 0;        // B, Shift+B
    virtual void cycleIblMode(int step) = 0;              // I, Shift+I
    virtual bool pointerOverUi() const = 0;               // the mouse is over the panel (shown)
    virtual void dragDivider(ui::Input& input, bool leftPressed, int width) = 0;   // the split's divider
    virtual void showMessage(const std::string& text) = 0;   // a transient notice
};

class WindowInput {
public:
    // `script`: --input-script's file, or none.
    WindowInput(GlfwWindow& window, ui::WindowControls& controls, CameraMotion& camera, WindowActions& actions,
                const std::optional<std::string>& script);

    // Key presses and releases of the frame into the hold record (times relative to `start`); `now` is the
    // frame's time on the same clock.
    void beginFrame(WindowEvents& events, double start, double now);
    // Acts on the frame's keys and returns what the panel sees (the mouse in framebuffer pixels, keys that drive
    // the panel, and those of script events due last frame).
    ui::Input panelInput(const WindowEvents& events, int width, int height);
    // Mouse look, the wheel's speed change, and the motion over [from, to], with the script's events applied at
    // their own times in between.
    void moveCamera(const WindowEvents& events, double from, double to, int width, int height);
    // The script's clock starts once the first frame (shader builds, environment precomputation) is done.
    void startScriptClock(double now);

    // The script screenshots due at the end of this frame, in script order (each written one frame after its
    // event, so that the panel and the stats strip have seen every earlier event). Events that fall in one frame
    // all get written, with that frame's image.
    std::vector<std::string> dueScriptScreenshots();
    // The script asked to quit and has no screenshot pending.
    bool scriptQuit() const { return scriptQuit_ && scriptScreenshots_.empty(); }
    bool mouseCaptured() const { return captured_; }

private:
    ui::Input handleKeys(const WindowEvents& events, int width, int height);
    void applyScriptEvent(const ui::ScriptEvent& e, double t, int width, int height);
    bool panelScriptInputPending() const;
    bool shiftHeld() const;
    double heldSeconds(ui::MoveKey key, double from, double to) const;
    void setCaptured(bool captured);

    GlfwWindow& window_;
    ui::WindowControls& controls_;
    CameraMotion& camera_;
    WindowActions& actions_;
    ui::KeyHolds keys_;
    double now_ = 0.0;
    std::unique_ptr<ui::ScriptPlayer> script_;
    struct PendingShot {
        std::string path;
        int framesToWait = 1;   // frame ends to let pass before writing it
    };
    std::vector<PendingShot> scriptScreenshots_;   // every requested one, in order (none is dropped)
    bool scriptQuit_ = false;
    double scriptOffset_ = -1.0;     // frame-clock time of script time 0 (the end of the first frame)
    ui::Input pendingScriptInput_;   // panel keys from the script, given to the panel next frame
    bool captured_ = false, rightLook_ = false, lookStarted_ = false;
    double escapeAt_ = -1e30;        // frame-clock time of the last Esc that asked to confirm quitting
    glm::dvec2 lastCursor_{0.0};
};

}  // namespace glimmer
