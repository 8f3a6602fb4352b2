// Reading whole files and locating the project's data folders (shaders/, content/).
#pragma once
#include <filesystem>
#include <string>

namespace glimmer {

// Throws glimmer::Error naming the path when it cannot be read.
std::string readTextFile(const std::filesystem::path& path);

// The shaders folder: $GLIMMER_SHADER_DIR, else <exe dir>/../share/glimmer/shaders, else <exe dir>/shaders,
// else <source>/shaders as configured at build time.
std::filesystem::path defaultShaderDir();
// The content folder (scene files): $GLIMMER_CONTENT_DIR, else the same places with content/.
std::filesystem::path defaultContentDir();

// How messages name a file: relative to the current folder when it lies below it, else the path as it is.
std::string displayPath(const std::filesystem::path& path);

}  // namespace glimmer
