// GLIMMER_MEASURE=1: the full sets of the tests that CI runs on a representative subset (every shared HDR map, every
// atrium camera, both NDFs, every material or change), and the measurements that nothing asserts. Each such test
// says beside its loop what CI covers and what the full run adds; docs/testing.md lists them. CI must stay within
// its time budget (docs/testing.md, "Running them"): a test that loops over a set pays for every element.
#pragma once
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace glimmer::test {

inline bool fullMeasurement() {
    const char* value = std::getenv("GLIMMER_MEASURE");
    return value && std::string(value) == "1";
}

// Of the shared HDR maps (sorted paths), the two that bound what the tests over maps measure: studio_small_03
// (tiny lamps up to 3568 against a mean of 1.9: the worst split-sum lookup, the lowest metered exposure) and
// rooitou_park (a wide sky with a small sun: the darkest auto-exposed atrium). Every map with GLIMMER_MEASURE=1
// (and every map if neither of the two is there).
inline std::vector<std::filesystem::path> mapsForThisRun(const std::vector<std::filesystem::path>& maps) {
    if (fullMeasurement()) return maps;
    std::vector<std::filesystem::path> bounding;
    for (const std::filesystem::path& map : maps) {
        const std::string name = map.filename().string();
        if (name.rfind("studio_small_03", 0) == 0 || name.rfind("rooitou_park", 0) == 0) bounding.push_back(map);
    }
    return bounding.empty() ? maps : bounding;
}

}  // namespace glimmer::test
