#include "gl/debug.h"

#include <cstdlib>

#include "core/log.h"

namespace glimmer::gl {

static void GLAD_API_PTR onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei,
                                        const GLchar* message, const void*) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    if (type == GL_DEBUG_TYPE_PUSH_GROUP || type == GL_DEBUG_TYPE_POP_GROUP) return;
    if (type == GL_DEBUG_TYPE_ERROR)
        log::error("GL: ", message);
    else
        log::debug("GL: ", message);
}

void enableDebugOutput() {
    bool wanted = false;
#ifndef NDEBUG
    wanted = true;
#endif
    if (const char* env = std::getenv("GLIMMER_GL_DEBUG")) wanted = env[0] == '1';
    if (!wanted || !GLAD_GL_KHR_debug) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onDebugMessage, nullptr);
}

}  // namespace glimmer::gl
