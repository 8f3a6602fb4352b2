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

static std::filesystem::path dirFromEnvOr(const char* variable, const char* fallback) {
    if (const char* value = std::getenv(variable); value && *value) return value;
    return std::filesystem::path(GLIMMER_SOURCE_DIR) / fallback;
}

std::filesystem::path defaultShaderDir() { return dirFromEnvOr("GLIMMER_SHADER_DIR", "shaders"); }
std::filesystem::path defaultContentDir() { return dirFromEnvOr("GLIMMER_CONTENT_DIR", "content"); }

}  // namespace glimmer
