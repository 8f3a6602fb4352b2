// libFuzzer target: reading an environment image (the CPU half of environment/environment.cpp's loading: format
// check, header limits, decoding). The extension follows the input's magic so every allowed reader is reached.
#include "core/error.h"
#include "core/image_io.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    glimmer::fuzz::quietLogs();
    std::string format = glimmer::sniffImageFormat(data, size);
    const char* extension = format == "openexr" ? ".exr" : format == "png" ? ".png" : ".hdr";
    try {
        glimmer::ImageF image = glimmer::readImage(glimmer::fuzz::writeInput(data, size, extension), glimmer::ImageUse::Environment);
        volatile float sum = 0.0f;
        for (float v : image.pixels) sum = sum + v;  // touch every decoded value
    } catch (const glimmer::Error&) {
    }
    return 0;
}
