// GL context creation only: each backend makes a 4.5 core context current and loads GL through glad.
// Nothing else in the engine knows which backend it runs on (Filament's platform split).
#pragma once
#include <memory>
#include <string>

namespace glimmer {

enum class Backend { Egl, OSMesa, Glfw };

const char* backendName(Backend backend);
// Parses "egl" / "osmesa"; throws UsageError naming --backend otherwise.
Backend parseHeadlessBackend(const std::string& name);

class GLContext {
public:
    virtual ~GLContext() = default;
    virtual Backend backend() const = 0;
    virtual void makeCurrent() = 0;
    // Renderer and version strings as GL reports them.
    std::string rendererString() const;
    std::string versionString() const;
};

// Headless context for offscreen rendering. With Backend::Egl, falls back to OSMesa (saying so on stderr) when
// EGL cannot give a 4.5 core context. Throws glimmer::Error when no backend works.
std::unique_ptr<GLContext> createHeadlessContext(Backend preferred);

// Individual backends (exposed for tests that compare them).
std::unique_ptr<GLContext> createEglContext();     // throws Error with the EGL reason
std::unique_ptr<GLContext> createOSMesaContext();  // throws Error with the reason

// Loads GL entry points through glad for the current context; throws when the context is below 4.5.
void loadGLFunctions(void* (*getProcAddress)(const char*), const char* backendLabel);

// How many GL contexts this process has created so far (every backend loads GL once per context). The tests use it
// to check that a test labelled as needing no GL context creates none (tests/support/test_needs.h).
int glContextsCreated();

}  // namespace glimmer
