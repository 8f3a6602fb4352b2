// A GLFW window with a 4.5 core context. Input is polled by the caller through glfwHandle().
#pragma once
#include <memory>
#include <string>

#include "platform/context.h"

struct GLFWwindow;

namespace glimmer {

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

    // True when a display is reachable (used to choose between the window and an offscreen render).
    static bool displayAvailable();

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace glimmer
