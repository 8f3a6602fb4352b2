#include "gl/pipeline_state.h"

namespace glimmer::gl {

void PipelineState::apply() const {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(viewport.x, viewport.y, viewport.z, viewport.w);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_STENCIL_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (depthTest) glEnable(GL_DEPTH_TEST); else glDisable(GL_DEPTH_TEST);
    glDepthFunc(depthFunc);
    glDepthMask(depthWrite ? GL_TRUE : GL_FALSE);
    glDepthRangef(depthRange.x, depthRange.y);
    if (cull) glEnable(GL_CULL_FACE); else glDisable(GL_CULL_FACE);
    glCullFace(cullFace);
    if (polygonOffset != glm::vec2(0.0f)) {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(polygonOffset.x, polygonOffset.y);
    } else {
        glDisable(GL_POLYGON_OFFSET_FILL);
    }
    glDisable(GL_BLEND);   // every draw buffer
    if (blend.enabled) {
        if (blend.onlyDrawBuffer >= 0) glEnablei(GL_BLEND, GLuint(blend.onlyDrawBuffer)); else glEnable(GL_BLEND);
        glBlendColor(blend.constant.x, blend.constant.y, blend.constant.z, blend.constant.w);
        glBlendFuncSeparate(blend.srcRgb, blend.dstRgb, blend.srcAlpha, blend.dstAlpha);
        glBlendEquation(GL_FUNC_ADD);
    }
}

PipelineState fullscreenState(GLuint framebuffer, int width, int height) {
    PipelineState state;
    state.framebuffer = framebuffer;
    state.viewport = {0, 0, width, height};
    return state;
}

}  // namespace glimmer::gl
