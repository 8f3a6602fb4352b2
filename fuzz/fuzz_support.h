// Helpers of the fuzz targets: the loaders read files by path, so each input is written to a file first.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace glimmer::fuzz {

// Writes the input to <per-process temp folder>/input<extension> and returns its path. The folder also holds
// the small files a fuzzed input may reference (a.bin, a.png), so URIs and texture paths reach real files.
std::filesystem::path writeInput(const uint8_t* data, size_t size, const char* extension);

// Quiet logging: warnings of every input would swamp the fuzzer's output.
void quietLogs();

}  // namespace glimmer::fuzz
