// A GLFW window with a 4.5 core context. Input is polled by the caller through glfwHandle().
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "platform/context.h"

struct GLFWwindow;

namespace glimmer {

// Input events gathered by GLFW callbacks between two takeEvents() calls (so that presses shorter than a frame
// are not lost); held keys and buttons are polled through glfwHandle().
struct WindowEvents {
    struct Key {
        int key;     // GLFW_KEY_*
        int mods;    // GLFW_MOD_* bits
        bool repeat; // auto-repeat of a held key
    };
    std::vector<Key> keys;
    // Every press and release with its arrival time (glfwGetTime seconds), for held-key movement.
    struct KeyChange {
        int key;
        bool down;
        double seconds;
    };
    std::vector<KeyChange> changes;
    bool focusLost = false;  // held keys are released: their release events go elsewhere
    bool leftPressed = false, rightPressed = false;
    double scrollY = 0.0;
};

class GlfwWindow final : public GLContext {
public:
    // Throws glimmer::Error when there is no display or no 4.5 core context.
    GlfwWindow(int width, int height, const std::string& title, bool visible = true);
    ~GlfwWindow() override;
    GlfwWindow(const GlfwWindow&) = delete;
    GlfwWindow& operator=(const GlfwWindow&) = delete;

    Backend backend() const override { return Backend::Glfw; }
    void makeCurrent() override;

    bool shouldClose() const;
    void requestClose();
    void swapBuffers();
    void setVsync(bool enabled);
    void framebufferSize(int& width, int& height) const;
    GLFWwindow* glfwHandle() const { return window_; }
    WindowEvents takeEvents();
    // Hides the cursor and reports unbounded motion (mouse look), or restores it.
    void setCursorCaptured(bool captured);
    void cursorPosition(double& x, double& y) const;
    void windowSize(int& width, int& height) const;

    // True when a display is reachable (used to choose between the window and an offscreen render).
    static bool displayAvailable();

private:
    GLFWwindow* window_ = nullptr;
    WindowEvents events_;
};

}  // namespace glimmer
