#include "platform/context.h"

#include <glad/gl.h>

#include <atomic>

#include "core/error.h"
#include "core/log.h"
#include "platform/driver_pinning.h"

namespace glimmer {

const char* backendName(Backend backend) {
    switch (backend) {
        case Backend::Egl: return "egl";
        case Backend::OSMesa: return "osmesa";
        case Backend::Glfw: return "glfw";
    }
    return "?";
}

Backend parseHeadlessBackend(const std::string& name) {
    if (name == "egl") return Backend::Egl;
    if (name == "osmesa") return Backend::OSMesa;
    throw UsageError("--backend: unknown backend '" + name + "' (expected egl or osmesa)");
}

static std::string glString(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "";
}
std::string GLContext::rendererString() const { return glString(GL_RENDERER); }
std::string GLContext::versionString() const { return glString(GL_VERSION); }

static std::atomic<int> g_contextsCreated{0};

int glContextsCreated() { return g_contextsCreated.load(); }

void loadGLFunctions(void* (*getProcAddress)(const char*), const char* backendLabel) {
    ++g_contextsCreated;
    int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(getProcAddress));
    if (version == 0) throw Error(std::string(backendLabel) + ": could not load GL functions");
    int major = GLAD_VERSION_MAJOR(version), minor = GLAD_VERSION_MINOR(version);
    if (major * 10 + minor < 45)
        throw Error(std::string(backendLabel) + ": GL " + std::to_string(major) + "." + std::to_string(minor) +
                    " context, 4.5 core required");
}

std::unique_ptr<GLContext> createHeadlessContext(Backend preferred) {
    pinGlDriversUnderSanitizers();
    if (preferred == Backend::OSMesa) return createOSMesaContext();
    try {
        return createEglContext();
    } catch (const Error& e) {
        log::warn(e.what(), "; falling back to OSMesa");
        return createOSMesaContext();
    }
}

}  // namespace glimmer
