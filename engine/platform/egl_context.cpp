// Headless EGL: a device display when EGL_EXT_platform_device lists one (real GPUs), else Mesa's surfaceless
// platform; no config and no surface (EGL_KHR_no_config_context + surfaceless_context), rendering goes to FBOs.
#include <glad/gl.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <vector>

#include "core/error.h"
#include "platform/context.h"

namespace glimmer {
namespace {

std::string eglErrorText() {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "0x%04x", eglGetError());
    return buffer;
}

class EglContext final : public GLContext {
public:
    EglContext() {
        auto getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (!getPlatformDisplay) throw Error("EGL: eglGetPlatformDisplayEXT is missing");
        const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        bool hasDevice = clientExtensions && std::strstr(clientExtensions, "EGL_EXT_platform_device");
        // Prefer a hardware device (NVIDIA's EGL lists GPUs here); Mesa's software device is the surfaceless path.
        if (hasDevice && !std::getenv("LIBGL_ALWAYS_SOFTWARE")) display_ = tryDeviceDisplay(getPlatformDisplay);
        if (display_ == EGL_NO_DISPLAY)
            display_ = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display_ == EGL_NO_DISPLAY) throw Error("EGL: no surfaceless or device display");
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display_, &major, &minor)) throw Error("EGL: eglInitialize failed (" + eglErrorText() + ")");
        if (!eglBindAPI(EGL_OPENGL_API)) throw Error("EGL: desktop OpenGL API unavailable");
        const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
#ifndef NDEBUG
                                     EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE,
#endif
                                     EGL_NONE};
        context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
        if (context_ == EGL_NO_CONTEXT) {
            std::string reason = eglErrorText();
            eglTerminate(display_);
            throw Error("EGL: cannot create a 4.5 core context (" + reason + ")");
        }
        makeCurrent();
        loadGLFunctions(reinterpret_cast<void* (*)(const char*)>(eglGetProcAddress), "EGL");
    }
    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    Backend backend() const override { return Backend::Egl; }
    void makeCurrent() override {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            throw Error("EGL: eglMakeCurrent failed (" + eglErrorText() + ")");
    }

private:
    static EGLDisplay tryDeviceDisplay(PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay) {
        auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        auto queryDeviceString =
            reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
        if (!queryDevices || !queryDeviceString) return EGL_NO_DISPLAY;
        EGLint count = 0;
        if (!queryDevices(0, nullptr, &count) || count <= 0) return EGL_NO_DISPLAY;
        std::vector<EGLDeviceEXT> devices(count);
        queryDevices(count, devices.data(), &count);
        for (EGLDeviceEXT device : devices) {
            const char* extensions = queryDeviceString(device, EGL_EXTENSIONS);
            // Mesa's software device advertises EGL_MESA_device_software; skip it so surfaceless handles that case.
            if (extensions && std::strstr(extensions, "EGL_MESA_device_software")) continue;
            EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
            if (display != EGL_NO_DISPLAY) return display;
        }
        return EGL_NO_DISPLAY;
    }

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GLContext> createEglContext() { return std::make_unique<EglContext>(); }

}  // namespace glimmer
