#include "platform/glfw_window.h"
#include "platform/driver_pinning.h"

#include <glad/gl.h>
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <utility>

#include "core/error.h"
#include "core/log.h"

namespace glimmer {
namespace {
std::string g_lastGlfwError;
void onGlfwError(int, const char* description) { g_lastGlfwError = description ? description : "unknown"; }

void initGlfwOnce() {
    static bool initialized = false;
    if (initialized) return;
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) throw Error("GLFW: cannot initialize (" + g_lastGlfwError + "); is a display available?");
    std::atexit(glfwTerminate);
    initialized = true;
}
}  // namespace

bool GlfwWindow::displayAvailable() {
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    return (x11 && *x11) || (wayland && *wayland);
}

GlfwWindow::GlfwWindow(int width, int height, const std::string& title, bool visible) {
    pinGlDriversUnderSanitizers();
    initGlfwOnce();
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);
#ifndef NDEBUG
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
#endif
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) throw Error("GLFW: cannot create a 4.5 core window (" + g_lastGlfwError + ")");
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int mods) {
        auto* self = static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w));
        if (action == GLFW_PRESS || action == GLFW_REPEAT) self->events_.keys.push_back({key, mods, action == GLFW_REPEAT});
        if (action != GLFW_REPEAT) self->events_.changes.push_back({key, action == GLFW_PRESS, glfwGetTime()});
    });
    glfwSetWindowFocusCallback(window_, [](GLFWwindow* w, int focused) {
        if (!focused) static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w))->events_.focusLost = true;
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
        auto* self = static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w));
        if (action != GLFW_PRESS) return;
        if (button == GLFW_MOUSE_BUTTON_LEFT) self->events_.leftPressed = true;
        if (button == GLFW_MOUSE_BUTTON_RIGHT) self->events_.rightPressed = true;
    });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double y) {
        static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w))->events_.scrollY += y;
    });
    makeCurrent();
    loadGLFunctions(reinterpret_cast<void* (*)(const char*)>(glfwGetProcAddress), "GLFW");
}

GlfwWindow::~GlfwWindow() {
    if (window_) glfwDestroyWindow(window_);
}

void GlfwWindow::makeCurrent() { glfwMakeContextCurrent(window_); }
bool GlfwWindow::shouldClose() const { return glfwWindowShouldClose(window_); }
void GlfwWindow::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void GlfwWindow::swapBuffers() { glfwSwapBuffers(window_); }
void GlfwWindow::setVsync(bool enabled) { glfwSwapInterval(enabled ? 1 : 0); }
WindowEvents GlfwWindow::takeEvents() { return std::exchange(events_, WindowEvents{}); }
void GlfwWindow::setCursorCaptured(bool captured) {
    glfwSetInputMode(window_, GLFW_CURSOR, captured ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
}
void GlfwWindow::cursorPosition(double& x, double& y) const { glfwGetCursorPos(window_, &x, &y); }
void GlfwWindow::windowSize(int& width, int& height) const { glfwGetWindowSize(window_, &width, &height); }
void GlfwWindow::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }

}  // namespace glimmer
