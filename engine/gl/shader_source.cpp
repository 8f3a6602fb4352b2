#include "gl/shader_source.h"

#include <algorithm>
#include <cstring>
#include <sstream>

#include "core/files.h"

namespace glimmer::gl {
namespace fs = std::filesystem;

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool isIdentifierStart(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
bool isIdentifierChar(char c) { return isIdentifierStart(c) || isDigit(c); }

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

struct Expansion {
    const fs::path& root;
    const ProgramDesc& desc;
    ExpandedSource& out;
    std::vector<fs::path> stack;   // the files being expanded, outermost first (cycle check, depth limit)

    // Appends `file` (and, recursively, its includes) to out.text. Each file gets a source-string number; #line
    // directives switch between them so the driver's line numbers are the files' own.
    void append(const fs::path& file, const std::string& includedFrom, int includeLine) {
        const std::string at = includedFrom + ":" + std::to_string(includeLine) + ": ";
        fs::path full = fs::weakly_canonical(root / file);
        if (std::find(stack.begin(), stack.end(), full) != stack.end())
            throw Error(at + "recursive #include of " + file.string());
        if (int(stack.size()) >= kMaxIncludeDepth)
            throw Error(at + "#include nested more than " + std::to_string(kMaxIncludeDepth) + " deep (at " + file.string() + ")");
        std::error_code ec;
        if (!fs::exists(full, ec)) {
            if (includedFrom.empty()) throw Error((root / file).string() + ": shader file not found");
            throw Error(at + "#include file not found: " + file.string());
        }
        // A file included twice is pasted once (include guards are implicit, like #pragma once).
        if (std::find(out.files.begin(), out.files.end(), full) != out.files.end() && !includedFrom.empty()) return;
        const bool userFile = !insideRoot(root, full);
        std::string text;
        try {
            text = readInputFile(full, userFile ? kMethodFileInput : kShaderFileInput);
        } catch (const Error& e) {
            if (includedFrom.empty()) throw;
            throw Error(at + "#include \"" + file.string() + "\": " + e.what());
        }
        const int index = int(out.files.size());
        out.files.push_back(full);
        stack.push_back(full);
        const std::string label = fileLabel(root, full);
        out.text += "#line 1 " + std::to_string(index) + "\n";
        int lineNumber = 0;
        IncludeDirective include;
        for (size_t start = 0; start < text.size();) {
            size_t end = text.find('\n', start);
            if (end == std::string::npos) end = text.size();
            const std::string line = text.substr(start, end - start);
            start = end + 1;
            ++lineNumber;
            if (!parseIncludeLine(line, include)) {
                out.text += line;
                out.text += '\n';
            } else {
                fs::path target = include.target;
                if (!include.quoted) {
                    auto macro = desc.includeMacros.find(include.target);
                    if (macro == desc.includeMacros.end())
                        throw Error(label + ":" + std::to_string(lineNumber) + ": #include " + include.target + " is not defined");
                    target = macro->second;
                }
                // Includes resolve against the shader root (the layout is flat enough that this is unambiguous); a
                // file outside it (a user method) finds files beside itself first, then the root's helpers.
                if (userFile && target.is_relative() && fs::exists(full.parent_path() / target, ec))
                    target = full.parent_path() / target;
                append(target, label, lineNumber);
                out.text += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(index) + "\n";
            }
            if (out.text.size() > kMaxStageSourceBytes)
                throw Error(label + ":" + std::to_string(lineNumber) + ": the assembled shader exceeds " +
                            byteSizeText(kMaxStageSourceBytes) + " (the includes' total)");
        }
        stack.pop_back();
    }
};

// Digits from `at`, as a number below 10^9; false when there are none or too many.
bool readNumber(const std::string& text, size_t& at, size_t& value) {
    size_t start = at;
    value = 0;
    while (at < text.size() && isDigit(text[at])) {
        if (at - start >= 9) return false;
        value = value * 10 + size_t(text[at] - '0');
        ++at;
    }
    return at > start;
}

bool skip(const std::string& text, size_t& at, char c) {
    if (at < text.size() && text[at] == c) {
        ++at;
        return true;
    }
    return false;
}

void skipBlanks(const std::string& text, size_t& at) {
    while (at < text.size() && isBlank(text[at])) ++at;
}

}  // namespace

bool parseIncludeLine(const std::string& line, IncludeDirective& include) {
    size_t at = 0;
    skipBlanks(line, at);
    if (!skip(line, at, '#')) return false;
    skipBlanks(line, at);
    static const char kWord[] = "include";
    if (line.compare(at, sizeof kWord - 1, kWord) != 0) return false;
    at += sizeof kWord - 1;
    size_t afterWord = at;
    skipBlanks(line, at);
    if (at == afterWord) return false;   // "#includes" or "#include" alone is not an include of anything
    if (skip(line, at, '"')) {
        size_t close = line.find('"', at);
        if (close == std::string::npos || close == at) return false;
        include.quoted = true;
        include.target = line.substr(at, close - at);
        at = close + 1;
    } else {
        if (at >= line.size() || !isIdentifierStart(line[at])) return false;
        size_t start = at;
        while (at < line.size() && isIdentifierChar(line[at])) ++at;
        include.quoted = false;
        include.target = line.substr(start, at - start);
    }
    skipBlanks(line, at);
    return at == line.size();
}

ExpandedSource expandShaderSource(const fs::path& root, const std::string& file, const ProgramDesc& desc) {
    ExpandedSource out;
    out.text = "#version 450 core\n";
    for (const std::string& define : desc.defines) out.text += "#define " + define + "\n";
    out.text += desc.preamble;
    if (!desc.preamble.empty() && desc.preamble.back() != '\n') out.text += '\n';
    fs::path canonicalRoot = fs::weakly_canonical(root);
    Expansion{canonicalRoot, desc, out, {}}.append(file, "", 0);
    return out;
}

std::string mapDriverLog(const std::string& log, const std::vector<fs::path>& files, const fs::path& root) {
    const fs::path canonicalRoot = fs::weakly_canonical(root);
    auto name = [&](size_t i) {
        if (i >= files.size()) return std::string("<generated>");
        if (!insideRoot(canonicalRoot, files[i])) return displayPath(files[i]);
        std::error_code ec;
        fs::path rel = fs::relative(files[i], canonicalRoot.parent_path(), ec);
        return (ec || rel.empty() ? files[i] : rel).string();
    };
    std::istringstream lines(log);
    std::string line, result;
    while (std::getline(lines, line)) {
        // Mesa: "0:41(2): error: ..."; NVIDIA: "0(41) : error C0000: ...".
        size_t at = 0, file = 0, number = 0, column = 0;
        if (readNumber(line, at, file)) {
            size_t mesa = at, nvidia = at;
            if (skip(line, mesa, ':') && readNumber(line, mesa, number) && skip(line, mesa, '(') &&
                readNumber(line, mesa, column) && skip(line, mesa, ')') && skip(line, mesa, ':')) {
                skipBlanks(line, mesa);
                result += name(file) + ":" + std::to_string(number) + ": " + line.substr(mesa) + "\n";
                continue;
            }
            if (skip(line, nvidia, '(') && readNumber(line, nvidia, number) && skip(line, nvidia, ')')) {
                skipBlanks(line, nvidia);
                if (skip(line, nvidia, ':')) {
                    skipBlanks(line, nvidia);
                    result += name(file) + ":" + std::to_string(number) + ": " + line.substr(nvidia) + "\n";
                    continue;
                }
            }
        }
        if (!line.empty()) result += line + "\n";
    }
    return result;
}

}  // namespace glimmer::gl
