#include "fuzz_support.h"

#include <unistd.h>

#include <fstream>
#include <string>

#include "core/log.h"

namespace glimmer::fuzz {

static std::filesystem::path folder() {
    static std::filesystem::path dir = [] {
        std::filesystem::path d = std::filesystem::temp_directory_path() / ("glimmer-fuzz-" + std::to_string(getpid()));
        std::filesystem::create_directories(d);
        // A 1x1 PNG and a small buffer for inputs that name "a.png" / "a.bin".
        static const unsigned char png[] = {0x89, 'P', 'N', 'G', 13, 10, 26, 10, 0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0, 1, 0, 0,
                                            0, 1, 8, 2, 0, 0, 0, 0x90, 0x77, 0x53, 0xDE, 0, 0, 0, 12, 'I', 'D', 'A', 'T', 0x08,
                                            0xD7, 0x63, 0xF8, 0xCF, 0xC0, 0x00, 0x00, 0x03, 0x01, 0x01, 0x00, 0x18, 0xDD, 0x8D,
                                            0xB0, 0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
        std::ofstream(d / "a.png", std::ios::binary).write(reinterpret_cast<const char*>(png), sizeof png);
        std::string bin(256, '\0');
        for (size_t i = 0; i < bin.size(); ++i) bin[i] = char(i * 37);
        std::ofstream(d / "a.bin", std::ios::binary) << bin;
        return d;
    }();
    return dir;
}

std::filesystem::path writeInput(const uint8_t* data, size_t size, const char* extension) {
    std::filesystem::path path = folder() / (std::string("input") + extension);
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
    return path;
}

void quietLogs() { log::setLevel(log::Level::Quiet); }

}  // namespace glimmer::fuzz
