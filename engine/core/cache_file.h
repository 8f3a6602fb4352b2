// On-disk caches of precomputed data (the wang2020 DPF tables today; environment, AO and shadow caches later).
//
// Use:
//     cache::CacheDir dir(cache::defaultCacheDir());
//     cache::CacheKey key{"wang2020-dpf", 2, "alpha=0.020 res=90x90x180"};
//     if (std::optional<std::string> bytes = dir.load("wang2020_dpf_a0.020.bin", key, expectedSize, validate))
//         ... use *bytes ...
//     else
//         ... generate, then dir.store("wang2020_dpf_a0.020.bin", key, payload);
//
// Rules every cache gets from this module, so a new cache needs no I/O code of its own:
//  - Each file carries a header: a magic, the container version, the cache's kind and layout version, the full
//    parameter text the payload was made from (every input it depends on, or hashes of large inputs: see
//    contentHash()), the payload size and a CRC-32 of the payload and of the header. load() returns the payload
//    only when all of them match; a file made under other parameters, truncated, or with a bad checksum is
//    reported with one warning and the caller regenerates. Bump `layoutVersion` whenever the payload's layout or
//    the code that generates it changes.
//  - The caller's `validate` sees the payload before it is trusted (reject NaN, out-of-range values): a file
//    whose checksum is right but whose values are not (written by a buggy or hostile program) is regenerated too.
//  - store() writes atomically (core/atomic_file.h): a killed write leaves at most a hidden temporary file, which
//    no load() reads and which a later store() in the same folder removes once its writer process is gone.
//  - An unwritable folder is reported once per process and folder; store() then returns false, so the caller
//    must not claim the result as cached.
//  - A successful load() marks the file used (its modification time becomes now): caches that keep a bounded
//    number of files (pruneLeastRecentlyUsed) drop the files no launch has read for the longest time, not the
//    oldest written. The default scene's environment, read at every start, then stays however many other maps
//    runs and tests write.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace glimmer::cache {

struct CacheKey {
    std::string kind;            // names the cache ("wang2020-dpf", "environment")
    uint32_t layoutVersion = 1;  // bump when the payload layout or its generator changes
    std::string parameters;      // every input the payload depends on, as text
};

// A cheap, stable 64-bit digest for keys: CRC-32 and Adler-32 of `bytes` (zlib) side by side, as 16 hex digits.
std::string contentHash(std::string_view bytes);
// contentHash of many pieces fed one at a time (no concatenated copy of large inputs): digest() equals
// contentHash of the pieces' bytes back to back.
class ContentHasher {
public:
    ContentHasher();
    ContentHasher& add(const void* bytes, size_t size);
    ContentHasher& add(std::string_view text) { return add(text.data(), text.size()); }
    template <typename T>
    ContentHasher& addVector(const std::vector<T>& values) {   // trivially copyable elements without padding
        add(uint64_t(values.size()));
        return add(values.data(), values.size() * sizeof(T));
    }
    ContentHasher& add(uint64_t value) { return add(&value, sizeof value); }
    ContentHasher& add(float value) { return add(&value, sizeof value); }
    std::string digest() const;

private:
    unsigned long crc_, adler_;
};

// contentHash of a file's bytes, or "" when it cannot be read.
std::string fileContentHash(const std::filesystem::path& path);

// $GLIMMER_CACHE_DIR, else $XDG_CACHE_HOME/glimmer, else $HOME/.cache/glimmer, else <temp>/glimmer.
std::filesystem::path defaultCacheDir();
// How many files of one kind a cache folder keeps (pruneLeastRecentlyUsed): `fallback`, or GLIMMER_CACHE_KEEP
// (1..1000) when set. A test run uses two dozen environments, each 38 MB: its folder keeps them all.
size_t keptFilesPerKind(size_t fallback);

class CacheDir {
public:
    explicit CacheDir(std::filesystem::path dir);
    const std::filesystem::path& path() const { return dir_; }

    // The payload stored in `name` under exactly `key`, when its size is `expectedSize` (0: any size up to
    // 1 GiB), its checksums hold and `validate` (when given) accepts it. Otherwise nullopt: silently when the
    // file does not exist, with one warning naming the file and the reason when it exists but is not usable.
    std::optional<std::string> load(const std::string& name, const CacheKey& key, uint64_t expectedSize = 0,
                                    const std::function<bool(std::string_view)>& validate = {}) const;

    // Keeps the `keep` most recently used files whose names start with `prefix` and end with `extension`
    // (load() and store() mark a file used) and removes the others. Returns how many it removed.
    size_t pruneLeastRecentlyUsed(const std::string& prefix, const std::string& extension, size_t keep) const;

    // Writes `payload` under `key` atomically. Returns false, after one warning per process and folder, when the
    // folder cannot be created or written.
    bool store(const std::string& name, const CacheKey& key, std::string_view payload) const;

private:
    void removeOrphanedTemporaries(const std::string& name) const;
    std::filesystem::path dir_;
};

// The serialized form (header + payload), exposed for tests and tools.
std::string encodeCacheFile(const CacheKey& key, std::string_view payload);
// The key a cache file was stored under (no payload checks), or nullopt when its header is unreadable.
std::optional<CacheKey> readCacheKey(const std::filesystem::path& file);

}  // namespace glimmer::cache
