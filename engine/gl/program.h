// GLSL programs built from files under a shader root, with #include "file", injected #defines and #line
// directives so that compile errors point at file:line. Files carry no #version line: the builder adds it.
#pragma once
#include <glad/gl.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"
#include "gl/handles.h"

namespace glimmer::gl {

struct ShaderStage {
    GLenum type;               // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER
    std::string file;          // relative to the shader root, e.g. "frame/lighting.frag"
};

struct ProgramDesc {
    std::string name;                     // for messages
    std::vector<ShaderStage> stages;
    std::vector<std::string> defines;     // "NAME" or "NAME VALUE"
    std::string preamble;                 // extra GLSL after the defines (generated parameter blocks)
    // `#include NAME` (no quotes) resolves through this map: how lighting.frag includes the selected method.
    std::map<std::string, std::string> includeMacros;
};

// A compile or link failure; what() is "file:line: message" (first error), details() the whole log.
class ShaderError : public Error {
public:
    ShaderError(const std::string& firstLine, std::string details) : Error(firstLine), details_(std::move(details)) {}
    const std::string& details() const { return details_; }

private:
    std::string details_;
};

// The text handed to the driver for one stage plus the files it was assembled from (index = GLSL source
// string number used in #line), so driver logs can be mapped back to file names.
struct ExpandedSource {
    std::string text;
    std::vector<std::filesystem::path> files;
};
ExpandedSource expandShaderSource(const std::filesystem::path& root, const std::string& file,
                                  const ProgramDesc& desc);

// Rewrites "0:41(2): error: ..." (Mesa) and "0(41) : error ..." (NVIDIA) into "file:41: error: ...".
std::string mapDriverLog(const std::string& log, const std::vector<std::filesystem::path>& files,
                         const std::filesystem::path& root);

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
