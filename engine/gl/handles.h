// RAII owners for GL objects (created with DSA). Move-only; zero means "none".
#pragma once
#include <glad/gl.h>

#include <utility>

#include <cstdint>
#include <initializer_list>
#include <vector>

namespace glimmer::gl {

template <void (*Destroy)(GLuint)>
class Handle {
public:
    Handle() = default;
    explicit Handle(GLuint id) : id_(id) {}
    ~Handle() { reset(); }
    Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) { reset(); id_ = std::exchange(other.id_, 0); }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;

    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset() { if (id_) Destroy(id_); id_ = 0; }

private:
    GLuint id_ = 0;
};

namespace detail {
inline void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
inline void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
inline void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
inline void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
inline void deleteProgram(GLuint id) { glDeleteProgram(id); }
inline void deleteQuery(GLuint id) { glDeleteQueries(1, &id); }
inline void deleteSampler(GLuint id) { glDeleteSamplers(1, &id); }
}  // namespace detail

using Buffer = Handle<detail::deleteBuffer>;
using Texture = Handle<detail::deleteTexture>;
using Framebuffer = Handle<detail::deleteFramebuffer>;
using VertexArray = Handle<detail::deleteVertexArray>;
using ProgramHandle = Handle<detail::deleteProgram>;
using Query = Handle<detail::deleteQuery>;
using Sampler = Handle<detail::deleteSampler>;

// Immutable-storage buffer holding `bytes` (data may be null). Flags: GL_DYNAMIC_STORAGE_BIT for glNamedBufferSubData.
Buffer createBuffer(GLsizeiptr bytes, const void* data, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
// 2D texture with immutable storage; levels = 1 for render targets.
Texture createTexture2D(GLenum internalFormat, int width, int height, int levels = 1);
// 1 x 1 RGBA16F texture holding one value (a neutral input where a pass has none, e.g. "unoccluded").
Texture createConstantTexture(float r, float g, float b, float a);
// Framebuffer with `colors` on attachments 0.. (all drawn to, in order) and an optional depth attachment, labelled
// for debuggers; throws an Error naming `label` when incomplete.
Framebuffer createFramebuffer(const char* label, std::initializer_list<GLuint> colors, GLuint depth = 0);

// A framebuffer over textures that other code owns and may reallocate (a pass drawing into frame resources): get()
// returns the same framebuffer while the attachments and their `versions` stay the same, and rebuilds it
// otherwise. A version must change whenever its texture is reallocated (FrameImage::serial does): texture names
// alone are not enough, since GL reuses the name of a deleted texture. A zero colour texture leaves its location
// without an attachment (GL_NONE in the draw buffers).
class AttachedFramebuffer {
public:
    GLuint get(const char* label, const std::vector<GLuint>& colors, GLuint depth, const std::vector<uint64_t>& versions);

private:
    std::vector<GLuint> colors_;
    GLuint depth_ = 0;
    std::vector<uint64_t> versions_;
    Framebuffer framebuffer_;
};

}  // namespace glimmer::gl
