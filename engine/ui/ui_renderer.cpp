#include "ui/ui_renderer.h"

#include <algorithm>

#include "common/bindings.glsl"
#include "ui/font.h"

namespace glimmer::ui {
namespace {
struct GpuQuad {
    float rect[4];
    uint32_t color;
    int32_t glyph;
    float scale;
    float unused;
};
static_assert(sizeof(GpuQuad) == 32);
}  // namespace

UiRenderer::UiRenderer(std::filesystem::path shaderRoot) : shaderRoot_(std::move(shaderRoot)) {
    program_ = build();
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    vao_ = gl::VertexArray(vao);
    glVertexArrayAttribFormat(vao, 0, 4, GL_FLOAT, GL_FALSE, offsetof(GpuQuad, rect));
    glVertexArrayAttribIFormat(vao, 1, 1, GL_UNSIGNED_INT, offsetof(GpuQuad, color));
    glVertexArrayAttribIFormat(vao, 2, 1, GL_INT, offsetof(GpuQuad, glyph));
    glVertexArrayAttribFormat(vao, 3, 1, GL_FLOAT, GL_FALSE, offsetof(GpuQuad, scale));
    for (GLuint a = 0; a < 4; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribBinding(vao, a, 0);
    }
    glVertexArrayBindingDivisor(vao, 0, 1);
}

gl::Program UiRenderer::build() const {
    gl::Program program(shaderRoot_, {"ui", {{GL_VERTEX_SHADER, "ui/ui.vert"}, {GL_FRAGMENT_SHADER, "ui/ui.frag"}}});
    auto glyphs = packedGlyphTable();
    glProgramUniform1uiv(program.id(), LOCATION_UI_GLYPH_ROWS, GLsizei(glyphs.size()), glyphs.data());
    return program;
}

void UiRenderer::reload() { program_ = build(); }

bool UiRenderer::reloadIfChanged(const std::vector<std::filesystem::path>& changed) {
    for (const auto& file : changed)
        if (std::find(dependencies().begin(), dependencies().end(), file) != dependencies().end()) {
            reload();
            return true;
        }
    return false;
}

void UiRenderer::draw(const DrawList& list, int width, int height) {
    const std::vector<Quad>& quads = list.quads();
    if (quads.empty() || width <= 0 || height <= 0) return;
    std::vector<GpuQuad> data;
    data.reserve(quads.size());
    for (const Quad& q : quads)
        data.push_back({{q.rect.x, q.rect.y, q.rect.w, q.rect.h}, q.color.packed(), q.glyph, float(q.scale), 0.0f});
    if (data.size() > capacity_) {
        capacity_ = std::max<size_t>(data.size() * 2, 1024);
        instances_ = gl::createBuffer(GLsizeiptr(capacity_ * sizeof(GpuQuad)), nullptr);
        glVertexArrayVertexBuffer(vao_.id(), 0, instances_.id(), 0, sizeof(GpuQuad));
    }
    glNamedBufferSubData(instances_.id(), 0, GLsizeiptr(data.size() * sizeof(GpuQuad)), data.data());

    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    program_.use();
    glProgramUniform2f(program_.id(), LOCATION_UI_SCREEN_SIZE, float(width), float(height));
    glBindVertexArray(vao_.id());
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(data.size()));  // the one UI draw
    glBindVertexArray(0);
    glDisable(GL_BLEND);
}

}  // namespace glimmer::ui
