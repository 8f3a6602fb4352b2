// libFuzzer target: a user method file (glints/user/method_header.cpp, its header block) and its assembly with
// its #includes the way the lighting pass builds it (gl/shader_source.cpp). An input may #include real files
// (fuzz_support's a.png, a.bin, /dev/zero, a folder): they must give one Error, never a hang or a huge read.
#include "core/error.h"
#include "core/files.h"
#include "fuzz_support.h"
#include "gl/shader_source.h"
#include "glints/user/method_header.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    glimmer::fuzz::quietLogs();
    const std::filesystem::path file = glimmer::fuzz::writeInput(data, size, ".glsl");
    try {
        glimmer::parseMethodHeader(glimmer::readInputFile(file, glimmer::kMethodFileInput), "input.glsl",
                                   [](const std::string& builtIn) { return builtIn == "deliot2023" ? "" : "not a built-in"; });
    } catch (const glimmer::Error&) {
    }
    try {
        glimmer::gl::ProgramDesc desc;
        desc.includeMacros = {{"GLINT_METHOD_FILE", "glints/smooth.glsl"}};
        glimmer::gl::expandShaderSource(std::filesystem::path(GLIMMER_SOURCE_DIR) / "shaders", file.string(), desc);
    } catch (const glimmer::Error&) {
    }
    return 0;
}
