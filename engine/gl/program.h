// GLSL programs built from files under a shader root (the source assembly, #include and #line: gl/shader_source.h).
#pragma once
#include <glad/gl.h>

#include <filesystem>
#include <string>
#include <vector>

#include "gl/handles.h"
#include "gl/shader_source.h"

namespace glimmer::gl {

class Program {
public:
    Program() = default;
    // Builds the program; throws ShaderError (or Error for missing files).
    Program(const std::filesystem::path& root, const ProgramDesc& desc);

    GLuint id() const { return handle_.id(); }
    void use() const { glUseProgram(handle_.id()); }
    explicit operator bool() const { return bool(handle_); }
    // Every file the program was built from (for hot reload).
    const std::vector<std::filesystem::path>& dependencies() const { return dependencies_; }
    const ProgramDesc& desc() const { return desc_; }

private:
    ProgramHandle handle_;
    ProgramDesc desc_;
    std::vector<std::filesystem::path> dependencies_;
};

}  // namespace glimmer::gl
