// GLSL source assembled from files under a shader root: #include "file" and #include MACRO, injected #defines and
// #line directives so that compile errors point at file:line. GL-free (the method-file fuzz target links it).
// Files carry no #version line: the builder adds it.
#pragma once
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/error.h"

namespace glimmer::gl {

struct ShaderStage {
    unsigned int type;         // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER (a GLenum)
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

// Limits of one stage's assembly (docs/hostile_input.md): every file is read by readInputFile (a regular file of
// at most 4 MiB), includes nest at most kMaxIncludeDepth deep (a cycle is an error naming the line), and the
// assembled text of a stage is at most kMaxStageSourceBytes.
constexpr int kMaxIncludeDepth = 32;
constexpr size_t kMaxStageSourceBytes = size_t(16) << 20;

// The text handed to the driver for one stage plus the files it was assembled from (index = GLSL source
// string number used in #line), so driver logs can be mapped back to file names.
struct ExpandedSource {
    std::string text;
    std::vector<std::filesystem::path> files;
};
ExpandedSource expandShaderSource(const std::filesystem::path& root, const std::string& file,
                                  const ProgramDesc& desc);

// The target of an `#include` line: `#include "file"` gives quoted = true and the file, `#include NAME` gives
// quoted = false and the macro name. Leading and trailing blanks are allowed, as around the '#'. Linear in the
// line's length (no backtracking regular expression: a 100 kB line must not exhaust the stack).
struct IncludeDirective {
    bool quoted = false;
    std::string target;
};
bool parseIncludeLine(const std::string& line, IncludeDirective& include);

// Rewrites "0:41(2): error: ..." (Mesa) and "0(41) : error ..." (NVIDIA) into "file:41: error: ...".
std::string mapDriverLog(const std::string& log, const std::vector<std::filesystem::path>& files,
                         const std::filesystem::path& root);

}  // namespace glimmer::gl
