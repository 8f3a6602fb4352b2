#include "gl/handles.h"

#include <string>
#include <vector>

#include "core/error.h"

namespace glimmer::gl {

Buffer createBuffer(GLsizeiptr bytes, const void* data, GLbitfield flags) {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    glNamedBufferStorage(id, bytes > 0 ? bytes : 16, data, flags);
    return Buffer(id);
}

Texture createTexture2D(GLenum internalFormat, int width, int height, int levels) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    glTextureStorage2D(id, levels, internalFormat, width, height);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, levels > 1 ? GL_LINEAR : GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return Texture(id);
}

Texture createConstantTexture(float r, float g, float b, float a) {
    Texture texture = createTexture2D(GL_RGBA16F, 1, 1);
    const float value[4] = {r, g, b, a};
    glClearTexImage(texture.id(), 0, GL_RGBA, GL_FLOAT, value);
    return texture;
}

Framebuffer createFramebuffer(const char* label, std::initializer_list<GLuint> colors, GLuint depth) {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    Framebuffer framebuffer(id);
    glObjectLabel(GL_FRAMEBUFFER, id, -1, label);
    std::vector<GLenum> drawBuffers;
    for (GLuint texture : colors) {
        const GLenum attachment = GL_COLOR_ATTACHMENT0 + GLenum(drawBuffers.size());
        glNamedFramebufferTexture(id, attachment, texture, 0);
        drawBuffers.push_back(attachment);
    }
    if (drawBuffers.size() > 1) glNamedFramebufferDrawBuffers(id, GLsizei(drawBuffers.size()), drawBuffers.data());
    if (depth) glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth, 0);
    const GLenum status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(std::string("framebuffer ") + label + " incomplete (status 0x" + std::to_string(status) + ")");
    return framebuffer;
}

GLuint AttachedFramebuffer::get(const char* label, const std::vector<GLuint>& colors, GLuint depth,
                                const std::vector<uint64_t>& versions) {
    if (framebuffer_ && colors == colors_ && depth == depth_ && versions == versions_) return framebuffer_.id();
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    Framebuffer framebuffer(id);
    glObjectLabel(GL_FRAMEBUFFER, id, -1, label);
    std::vector<GLenum> drawBuffers;
    for (size_t i = 0; i < colors.size(); ++i) {
        const GLenum attachment = GL_COLOR_ATTACHMENT0 + GLenum(i);
        if (colors[i]) glNamedFramebufferTexture(id, attachment, colors[i], 0);
        drawBuffers.push_back(colors[i] ? attachment : GL_NONE);
    }
    glNamedFramebufferDrawBuffers(id, GLsizei(drawBuffers.size()), drawBuffers.data());
    if (drawBuffers.empty()) glNamedFramebufferDrawBuffer(id, GL_NONE);
    if (depth) glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth, 0);
    const GLenum status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error(std::string("framebuffer ") + label + " incomplete (status 0x" + std::to_string(status) + ")");
    framebuffer_ = std::move(framebuffer);
    colors_ = colors;
    depth_ = depth;
    versions_ = versions;
    return framebuffer_.id();
}

}  // namespace glimmer::gl
