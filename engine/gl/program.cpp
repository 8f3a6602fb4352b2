#include "gl/program.h"

#include <algorithm>
#include <regex>
#include <sstream>

#include "core/files.h"

namespace glimmer::gl {
namespace fs = std::filesystem;

namespace {

bool insideRoot(const fs::path& root, const fs::path& file) {
    auto r = root.begin(), f = file.begin();
    for (; r != root.end(); ++r, ++f)
        if (f == file.end() || *r != *f) return false;
    return true;
}

// How messages name a file: relative to the shader root inside it, else as displayPath gives it (user method files).
std::string fileLabel(const fs::path& root, const fs::path& full) {
    return insideRoot(root, full) ? fs::relative(full, root).string() : displayPath(full);
}

// Appends `file` (and, recursively, its includes) to `out`. Each file gets a source-string number; #line
// directives switch between them so the driver's line numbers are the files' own.
void appendFile(const fs::path& root, const fs::path& file, const ProgramDesc& desc, ExpandedSource& out,
                std::vector<fs::path>& stack, const fs::path& includedFrom, int includeLine) {
    fs::path full = fs::weakly_canonical(root / file);
    if (std::find(stack.begin(), stack.end(), full) != stack.end())
        throw Error(includedFrom.string() + ":" + std::to_string(includeLine) + ": recursive #include of " +
                    file.string());
    if (!fs::exists(full)) {
        if (includedFrom.empty()) throw Error((root / file).string() + ": shader file not found");
        throw Error(includedFrom.string() + ":" + std::to_string(includeLine) + ": #include file not found: " +
                    file.string());
    }
    auto found = std::find(out.files.begin(), out.files.end(), full);
    // A file included twice is pasted once (include guards are implicit, like #pragma once).
    if (found != out.files.end() && !includedFrom.empty()) return;
    int index = static_cast<int>(out.files.size());
    out.files.push_back(full);
    stack.push_back(full);

    std::istringstream lines(readTextFile(full));
    std::string line;
    int lineNumber = 0;
    out.text += "#line 1 " + std::to_string(index) + "\n";
    static const std::regex includePattern(R"re(^\s*#\s*include\s+(?:"([^"]+)"|([A-Za-z_][A-Za-z0-9_]*))\s*$)re");
    std::smatch match;
    while (std::getline(lines, line)) {
        ++lineNumber;
        if (std::regex_match(line, match, includePattern)) {
            fs::path target = match[1].str();
            if (match[2].matched) {
                auto macro = desc.includeMacros.find(match[2].str());
                if (macro == desc.includeMacros.end())
                    throw Error(fileLabel(root, full) + ":" + std::to_string(lineNumber) +
                                ": #include " + match[2].str() + " is not defined");
                target = macro->second;
            }
            // Includes resolve against the shader root (the layout is flat enough that this is unambiguous); a
            // file outside it (a user method) finds files beside itself first, then the root's helpers.
            if (!insideRoot(root, full) && target.is_relative() && fs::exists(full.parent_path() / target))
                target = full.parent_path() / target;
            appendFile(root, target, desc, out, stack, fileLabel(root, full), lineNumber);
            out.text += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(index) + "\n";
        } else {
            out.text += line;
            out.text += '\n';
        }
    }
    stack.pop_back();
}

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

ExpandedSource expandShaderSource(const fs::path& root, const std::string& file, const ProgramDesc& desc) {
    ExpandedSource out;
    out.text = "#version 450 core\n";
    for (const std::string& define : desc.defines) out.text += "#define " + define + "\n";
    out.text += desc.preamble;
    if (!desc.preamble.empty() && desc.preamble.back() != '\n') out.text += '\n';
    std::vector<fs::path> stack;
    appendFile(fs::weakly_canonical(root), file, desc, out, stack, {}, 0);
    return out;
}

std::string mapDriverLog(const std::string& log, const std::vector<fs::path>& files, const fs::path& root) {
    // Mesa: "0:41(2): error: ..."; NVIDIA: "0(41) : error C0000: ...".
    static const std::regex mesa(R"(^(\d+):(\d+)\((\d+)\):\s*(.*)$)");
    static const std::regex nvidia(R"(^(\d+)\((\d+)\)\s*:\s*(.*)$)");
    std::istringstream lines(log);
    std::string line, result;
    std::smatch m;
    auto name = [&](const std::string& index) {
        size_t i = std::stoul(index);
        if (i >= files.size()) return std::string("<generated>");
        fs::path canonicalRoot = fs::weakly_canonical(root);
        if (!insideRoot(canonicalRoot, files[i])) return displayPath(files[i]);
        std::error_code ec;
        fs::path rel = fs::relative(files[i], canonicalRoot.parent_path(), ec);
        return (ec || rel.empty() ? files[i] : rel).string();
    };
    while (std::getline(lines, line)) {
        if (std::regex_match(line, m, mesa))
            result += name(m[1]) + ":" + m[2].str() + ": " + m[4].str() + "\n";
        else if (std::regex_match(line, m, nvidia))
            result += name(m[1]) + ":" + m[2].str() + ": " + m[3].str() + "\n";
        else if (!line.empty())
            result += line + "\n";
    }
    return result;
}

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
