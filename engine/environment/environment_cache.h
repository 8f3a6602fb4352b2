// Disk cache of the environment precomputation (cubemap, its mips, the prefiltered specular levels and the SH
// irradiance): the GPU work takes seconds per map on a software renderer and is the same on every launch.
//
// The key holds everything the maps depend on: the spec (for a file, a hash of its bytes, not its path or date;
// for the procedural sky, the sun), the map sizes and sample counts, and a hash of the fully expanded source of
// every compute shader that builds them, so an edited shader or a replaced image never reads a stale cache. The
// payload is every level of the two textures as RGBA32F plus the nine SH coefficients, in the texture layout the
// caller allocated; it is accepted only when its size matches that layout exactly and every value is finite and
// non-negative (core/cache_file.h adds the checksums and the atomic write). One file per key; the folder keeps
// the kMaxFiles most recently used environment files (read or written: cache::CacheDir::pruneLeastRecentlyUsed;
// GLIMMER_CACHE_KEEP overrides the count).
#pragma once
#include <glad/gl.h>
#include <glm/glm.hpp>

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/cache_file.h"

namespace glimmer {

class EnvironmentCache {
public:
    static constexpr int kMaxFiles = 6;
    // GLIMMER_ENV_CACHE=0 turns the cache off (timing the precomputation itself); the folder is
    // cache::defaultCacheDir().
    static bool enabledByEnvironment();

    EnvironmentCache(std::filesystem::path dir, std::string parameters);
    const std::string& fileName() const { return fileName_; }

    // Fills every level of `textures` (already allocated with their final storage) and `sh` from the cache.
    // False (textures untouched) on a miss or an unusable file (which cache_file reports once).
    bool load(const std::vector<GLuint>& textures, std::array<glm::vec3, 9>& sh) const;
    // Reads every level of `textures` back and stores them with `sh`. False when the folder is not writable.
    bool store(const std::vector<GLuint>& textures, const std::array<glm::vec3, 9>& sh) const;

private:
    void pruneOldFiles() const;
    cache::CacheDir dir_;
    cache::CacheKey key_;
    std::string fileName_;
};

// Bytes of every level of `texture` as RGBA32F (2D: width x height; cube: x 6; cube array: x its layer-faces).
size_t textureLevelBytes(GLuint texture);

}  // namespace glimmer
