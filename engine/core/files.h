// Reading the files the engine takes as input, and locating the project's data folders (shaders/, content/).
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace glimmer {

// What kind of file is being read, for messages ("method file"), and the most bytes it may have. The limits are
// stated for users in docs/hostile_input.md.
struct InputFileKind {
    const char* what;
    uint64_t maxBytes;
};
inline constexpr InputFileKind kMethodFileInput{"method file", uint64_t(4) << 20};      // user method + includes
inline constexpr InputFileKind kShaderFileInput{"shader file", uint64_t(4) << 20};      // shaders/, #includes
inline constexpr InputFileKind kSceneFileInput{"scene file", uint64_t(64) << 20};       // .json scene files
inline constexpr InputFileKind kCameraPathInput{"camera path", uint64_t(64) << 20};     // render --path
inline constexpr InputFileKind kInputScriptInput{"input script", uint64_t(16) << 20};   // view --input-script
inline constexpr InputFileKind kModelFileInput{"glTF file", uint64_t(1) << 30};         // .gltf / .glb
inline constexpr InputFileKind kModelPartInput{"glTF buffer or image", uint64_t(1) << 30};  // a model's external files

// The one way the engine reads a file it is given (method files and what they include, shaders, scene files,
// camera paths, input scripts, glTF files and their buffers): the path must name a regular file (a folder, FIFO
// or device is refused before a byte is read, and opening never blocks), no larger than kind.maxBytes (checked
// on the open file before reading, and again while reading, so a file that grows is caught too). Every failure
// throws glimmer::Error with one line naming the path, the kind and, for sizes, the limit.
std::string readInputFile(const std::filesystem::path& path, const InputFileKind& kind);
// The same into a byte vector (glTF buffers, which tinygltf takes as one).
void readInputFile(const std::filesystem::path& path, const InputFileKind& kind, std::vector<unsigned char>& bytes);

// "4 MiB", "1 GiB", "1000 bytes": how messages state a limit.
std::string byteSizeText(uint64_t bytes);

// The shaders folder: $GLIMMER_SHADER_DIR, else <exe dir>/../share/glimmer/shaders, else <exe dir>/shaders,
// else <source>/shaders as configured at build time.
std::filesystem::path defaultShaderDir();
// The content folder (scene files): $GLIMMER_CONTENT_DIR, else the same places with content/.
std::filesystem::path defaultContentDir();

// How messages name a file: relative to the current folder when it lies below it, else the path as it is.
std::string displayPath(const std::filesystem::path& path);

}  // namespace glimmer
