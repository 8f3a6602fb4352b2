// libFuzzer target: the .json scene-file loader (generated meshes, materials, lights, cameras, models).
#include "core/error.h"
#include "fuzz_support.h"
#include "scene/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    glimmer::fuzz::quietLogs();
    try {
        glimmer::loadSceneFile(glimmer::fuzz::writeInput(data, size, ".json"));
    } catch (const glimmer::Error&) {
    }
    return 0;
}
