// Draws a ui::DrawList in one instanced draw call with one program (shaders/ui/ui.vert + ui.frag) into the
// currently bound framebuffer. The font table is uploaded as uniforms; quads stream through one instance buffer.
#pragma once
#include <filesystem>
#include <vector>

#include "gl/handles.h"
#include "gl/program.h"
#include "ui/ui.h"

namespace glimmer::ui {

class UiRenderer {
public:
    // Builds the program; throws gl::ShaderError with file:line.
    explicit UiRenderer(std::filesystem::path shaderRoot);
    void draw(const DrawList& list, int width, int height);
    // Rebuilds the program when one of `changed` is among its files; keeps the old program and rethrows on
    // failure. Returns whether it rebuilt.
    bool reloadIfChanged(const std::vector<std::filesystem::path>& changed);
    void reload();
    const std::vector<std::filesystem::path>& dependencies() const { return program_.dependencies(); }

private:
    gl::Program build() const;

    std::filesystem::path shaderRoot_;
    gl::Program program_;
    gl::VertexArray vao_;
    gl::Buffer instances_;
    size_t capacity_ = 0;
};

}  // namespace glimmer::ui
