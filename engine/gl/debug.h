// KHR_debug output routed to the log (debug builds, or GLIMMER_GL_DEBUG=1), and debug groups naming passes.
#pragma once
#include <glad/gl.h>

namespace glimmer::gl {

void enableDebugOutput();

// Scoped debug group: passes show by name in apitrace / RenderDoc and in debug-output messages.
class DebugGroup {
public:
    explicit DebugGroup(const char* name) { glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name); }
    ~DebugGroup() { glPopDebugGroup(); }
    DebugGroup(const DebugGroup&) = delete;
    DebugGroup& operator=(const DebugGroup&) = delete;
};

}  // namespace glimmer::gl
