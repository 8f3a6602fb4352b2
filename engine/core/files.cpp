#include "core/files.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace glimmer {

std::string readTextFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path.string() + ": cannot open file");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw Error(path.string() + ": read error");
    return text.str();
}

std::string displayPath(const std::filesystem::path& path) {
    std::error_code ec;
    std::filesystem::path relative = std::filesystem::relative(path, std::filesystem::current_path(ec), ec);
    if (ec || relative.empty() || *relative.begin() == "..") return path.string();
    return relative.string();
}

// $variable, else beside the running executable (an installed <prefix>/bin/glimmer finds
// <prefix>/share/glimmer/<name>; a copied folder may hold <name> next to the executable), else the source tree
// the build was configured from.
static std::filesystem::path dirFromEnvOr(const char* variable, const char* name) {
    if (const char* value = std::getenv(variable); value && *value) return value;
    std::error_code ec;
    std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        std::filesystem::path exeDir = exe.parent_path();
        for (const std::filesystem::path& candidate : {exeDir / ".." / "share" / "glimmer" / name, exeDir / name})
            if (std::filesystem::is_directory(candidate, ec)) return candidate.lexically_normal();
    }
    return std::filesystem::path(GLIMMER_SOURCE_DIR) / name;
}

std::filesystem::path defaultShaderDir() { return dirFromEnvOr("GLIMMER_SHADER_DIR", "shaders"); }
std::filesystem::path defaultContentDir() { return dirFromEnvOr("GLIMMER_CONTENT_DIR", "content"); }

}  // namespace glimmer
