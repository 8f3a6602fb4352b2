// libFuzzer target: the glTF loader on one .gltf (JSON) or .glb (binary, when the input starts with "glTF").
#include <cstring>

#include "core/error.h"
#include "fuzz_support.h"
#include "scene/gltf_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    glimmer::fuzz::quietLogs();
    bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    try {
        glimmer::loadGltfScene(glimmer::fuzz::writeInput(data, size, binary ? ".glb" : ".gltf"));
    } catch (const glimmer::Error&) {
        // The expected outcome for bad input. Any other exception escapes and is reported as a crash.
    }
    return 0;
}
