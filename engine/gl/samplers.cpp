#include "gl/samplers.h"

namespace glimmer::gl {

Sampler createLinearClampSampler() {
    GLuint id = 0;
    glCreateSamplers(1, &id);
    glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    return Sampler(id);
}

}  // namespace glimmer::gl
