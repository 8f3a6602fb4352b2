#include "gl/program.h"

#include <algorithm>
#include <sstream>

namespace glimmer::gl {
namespace fs = std::filesystem;

namespace {

std::string firstErrorLine(const std::string& mapped) {
    std::istringstream lines(mapped);
    std::string line, first;
    while (std::getline(lines, line)) {
        if (line.empty()) continue;
        if (first.empty()) first = line;
        if (line.find("error") != std::string::npos) return line;
    }
    return first.empty() ? "unknown shader error" : first;
}

GLuint compileStage(const fs::path& root, const ShaderStage& stage, const ProgramDesc& desc,
                    std::vector<fs::path>& dependencies) {
    ExpandedSource source = expandShaderSource(root, stage.file, desc);
    for (const fs::path& f : source.files)
        if (std::find(dependencies.begin(), dependencies.end(), f) == dependencies.end()) dependencies.push_back(f);
    GLuint shader = glCreateShader(stage.type);
    const char* text = source.text.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(std::max(length, 1), '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        glDeleteShader(shader);
        std::string mapped = mapDriverLog(log.c_str(), source.files, root);
        throw ShaderError(firstErrorLine(mapped), mapped);
    }
    return shader;
}

}  // namespace

Program::Program(const fs::path& root, const ProgramDesc& desc) : desc_(desc) {
    std::vector<GLuint> shaders;
    try {
        for (const ShaderStage& stage : desc.stages) shaders.push_back(compileStage(root, stage, desc, dependencies_));
    } catch (...) {
        for (GLuint s : shaders) glDeleteShader(s);
        throw;
    }
    GLuint program = glCreateProgram();
    for (GLuint s : shaders) glAttachShader(program, s);
    glLinkProgram(program);
    for (GLuint s : shaders) { glDetachShader(program, s); glDeleteShader(s); }
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
        std::string log(std::max(length, 1), '\0');
        glGetProgramInfoLog(program, length, nullptr, log.data());
        glDeleteProgram(program);
        throw ShaderError(desc.name + ": link failed: " + firstErrorLine(log.c_str()), log.c_str());
    }
    glObjectLabel(GL_PROGRAM, program, -1, desc.name.c_str());
    handle_ = ProgramHandle(program);
}

}  // namespace glimmer::gl
