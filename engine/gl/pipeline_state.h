// The whole fixed-function state a draw depends on, applied in full by every pass before it draws, so that no pass
// inherits a leftover of the previous one (depth test left on, blending left on for one draw buffer, a smaller
// viewport of a shadow or cube-face render, a UI scissor).
#pragma once
#include <glad/gl.h>

#include <glm/glm.hpp>

namespace glimmer::gl {

struct BlendState {
    bool enabled = false;
    int onlyDrawBuffer = -1;   // >= 0: blend this draw buffer only (the others of a multi-target pass write)
    GLenum srcRgb = GL_ONE, dstRgb = GL_ZERO, srcAlpha = GL_ONE, dstAlpha = GL_ZERO;
    glm::vec4 constant{0.0f};  // glBlendColor (GL_CONSTANT_ALPHA weights)
};

struct PipelineState {
    GLuint framebuffer = 0;
    glm::ivec4 viewport{0, 0, 1, 1};
    bool depthTest = false;
    GLenum depthFunc = GL_GREATER;   // reversed Z everywhere (clip control zero-to-one, depth cleared to 0)
    bool depthWrite = false;
    // glDepthRange: (d, d) gives every fragment the depth d (the lighting pass's shading classes).
    glm::vec2 depthRange{0.0f, 1.0f};
    bool cull = false;
    GLenum cullFace = GL_BACK;
    BlendState blend;
    // glPolygonOffset(factor, units) on filled polygons; (0, 0) turns it off. Shadow maps push casters away from
    // the light (negative in reversed Z) by their depth slope.
    glm::vec2 polygonOffset{0.0f};

    // Binds the framebuffer and sets every field above, plus the state no pass changes: clip control
    // (lower-left, zero-to-one), colour writes on, no scissor, no stencil.
    void apply() const;
};

// Convenience: a full-screen pass into `framebuffer` of width x height, no depth, no blending, no culling.
PipelineState fullscreenState(GLuint framebuffer, int width, int height);

}  // namespace glimmer::gl
