#include "core/cache_file.h"

#include <signal.h>
#include <zlib.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <fstream>
#include <mutex>
#include <set>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/log.h"

namespace glimmer::cache {

namespace {

constexpr char kMagic[8] = {'G', 'L', 'M', 'R', 'C', 'A', 'C', 'H'};
constexpr uint32_t kContainerVersion = 1;
constexpr uint64_t kMaxPayload = uint64_t(1) << 30;
constexpr uint32_t kMaxText = 1 << 16;  // kind and parameter strings

void put32(std::string& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(char((v >> (8 * i)) & 0xFF));
}
void put64(std::string& out, uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(char((v >> (8 * i)) & 0xFF));
}
void putText(std::string& out, const std::string& text) {
    put32(out, uint32_t(text.size()));
    out += text;
}

uint32_t crc(std::string_view bytes) {
    return uint32_t(crc32_z(crc32_z(0, nullptr, 0), reinterpret_cast<const Bytef*>(bytes.data()), bytes.size()));
}

// Sequential little-endian reads from a stream; any short read makes ok() false.
class HeaderReader {
public:
    explicit HeaderReader(std::istream& in) : in_(in) {}
    bool ok() const { return ok_; }
    const std::string& bytes() const { return bytes_; }
    uint64_t number(int size) {
        char b[8] = {};
        if (!read(b, size_t(size))) return 0;
        uint64_t v = 0;
        for (int i = size - 1; i >= 0; --i) v = (v << 8) | uint8_t(b[i]);
        return v;
    }
    std::string text() {
        uint64_t n = number(4);
        if (!ok_ || n > kMaxText) { ok_ = false; return ""; }
        std::string s(size_t(n), '\0');
        read(s.data(), s.size());
        return s;
    }
    bool read(char* out, size_t n) {
        if (!ok_) return false;
        in_.read(out, std::streamsize(n));
        if (size_t(in_.gcount()) != n) { ok_ = false; return false; }
        bytes_.append(out, n);
        return true;
    }

private:
    std::istream& in_;
    std::string bytes_;
    bool ok_ = true;
};

bool processAlive(long pid) { return pid > 0 && (kill(pid_t(pid), 0) == 0 || errno == EPERM); }

}  // namespace

std::string contentHash(std::string_view bytes) {
    const Bytef* data = reinterpret_cast<const Bytef*>(bytes.data());
    uLong a = adler32_z(adler32_z(0, nullptr, 0), data, bytes.size());
    uLong c = crc32_z(crc32_z(0, nullptr, 0), data, bytes.size());
    char text[17];
    std::snprintf(text, sizeof text, "%08lx%08lx", c & 0xFFFFFFFFul, a & 0xFFFFFFFFul);
    return text;
}

ContentHasher::ContentHasher() : crc_(crc32_z(0, nullptr, 0)), adler_(adler32_z(0, nullptr, 0)) {}

ContentHasher& ContentHasher::add(const void* bytes, size_t size) {
    const Bytef* data = static_cast<const Bytef*>(bytes);
    crc_ = crc32_z(crc_, data, size);
    adler_ = adler32_z(adler_, data, size);
    return *this;
}

std::string ContentHasher::digest() const {
    char text[17];
    std::snprintf(text, sizeof text, "%08lx%08lx", crc_ & 0xFFFFFFFFul, adler_ & 0xFFFFFFFFul);
    return text;
}

std::string fileContentHash(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "";
    uLong a = adler32_z(0, nullptr, 0), c = crc32_z(0, nullptr, 0);
    std::vector<char> buffer(1 << 20);
    while (in) {
        in.read(buffer.data(), std::streamsize(buffer.size()));
        size_t n = size_t(in.gcount());
        a = adler32_z(a, reinterpret_cast<const Bytef*>(buffer.data()), n);
        c = crc32_z(c, reinterpret_cast<const Bytef*>(buffer.data()), n);
    }
    if (in.bad()) return "";
    char text[17];
    std::snprintf(text, sizeof text, "%08lx%08lx", c & 0xFFFFFFFFul, a & 0xFFFFFFFFul);
    return text;
}

std::filesystem::path defaultCacheDir() {
    if (const char* d = std::getenv("GLIMMER_CACHE_DIR"); d && *d) return d;
    if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::filesystem::path(d) / "glimmer";
    if (const char* d = std::getenv("HOME"); d && *d) return std::filesystem::path(d) / ".cache" / "glimmer";
    return std::filesystem::temp_directory_path() / "glimmer";
}

size_t keptFilesPerKind(size_t fallback) {
    const char* text = std::getenv("GLIMMER_CACHE_KEEP");
    if (!text || !*text) return fallback;
    char* end = nullptr;
    const long value = std::strtol(text, &end, 10);
    if (*end != '\0' || value < 1 || value > 1000) {
        log::warn("GLIMMER_CACHE_KEEP='", std::string(text).substr(0, 32), "' is not a count in [1, 1000]; keeping ",
                  fallback, " files of each kind");
        return fallback;
    }
    return size_t(value);
}

std::string encodeCacheFile(const CacheKey& key, std::string_view payload) {
    std::string out(kMagic, sizeof kMagic);
    put32(out, kContainerVersion);
    put32(out, key.layoutVersion);
    putText(out, key.kind);
    putText(out, key.parameters);
    put64(out, payload.size());
    put32(out, crc(payload));
    put32(out, crc(out));  // the header's own checksum covers everything before it
    out += payload;
    return out;
}

CacheDir::CacheDir(std::filesystem::path dir) : dir_(std::move(dir)) {}

std::optional<std::string> CacheDir::load(const std::string& name, const CacheKey& key, uint64_t expectedSize,
                                          const std::function<bool(std::string_view)>& validate) const {
    const std::filesystem::path file = dir_ / name;
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) return std::nullopt;
    auto reject = [&](const std::string& why) -> std::optional<std::string> {
        log::warn("cache ", file.string(), ": ", why, "; regenerating");
        return std::nullopt;
    };
    if (!std::filesystem::is_regular_file(file, ec)) return reject("not a regular file");
    uint64_t fileSize = std::filesystem::file_size(file, ec);
    std::ifstream in(file, std::ios::binary);
    if (!in) return reject("cannot be read");
    HeaderReader header(in);
    char magic[sizeof kMagic];
    if (!header.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0)
        return reject("not a Glimmer cache file (bad magic)");
    uint64_t container = header.number(4), layout = header.number(4);
    std::string kind = header.text(), parameters = header.text();
    uint64_t payloadSize = header.number(8), payloadCrc = header.number(4);
    uint32_t expectedHeaderCrc = crc(header.bytes());
    uint64_t headerCrc = header.number(4);
    if (!header.ok()) return reject("truncated header");
    if (headerCrc != expectedHeaderCrc) return reject("corrupt header (checksum mismatch)");
    if (container != kContainerVersion) return reject("container version " + std::to_string(container) + ", expected " + std::to_string(kContainerVersion));
    if (kind != key.kind) return reject("holds a '" + kind + "' cache, expected '" + key.kind + "'");
    if (layout != key.layoutVersion) return reject("layout version " + std::to_string(layout) + ", expected " + std::to_string(key.layoutVersion));
    if (parameters != key.parameters) return reject("made with other parameters (" + parameters + ")");
    uint64_t headerSize = header.bytes().size();
    if (payloadSize > kMaxPayload || (expectedSize && payloadSize != expectedSize))
        return reject("payload of " + std::to_string(payloadSize) + " bytes, expected " + std::to_string(expectedSize));
    if (fileSize != headerSize + payloadSize) return reject("truncated or padded payload");
    std::string payload(size_t(payloadSize), '\0');
    in.read(payload.data(), std::streamsize(payload.size()));
    if (uint64_t(in.gcount()) != payloadSize) return reject("truncated payload");
    if (crc(payload) != payloadCrc) return reject("corrupt payload (checksum mismatch)");
    if (validate && !validate(payload)) return reject("values out of range");
    // Last use, for pruneLeastRecentlyUsed: a read-only folder simply keeps the write time.
    std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now(), ec);
    return payload;
}

std::optional<CacheKey> readCacheKey(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    HeaderReader header(in);
    char magic[sizeof kMagic];
    if (!header.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0) return std::nullopt;
    header.number(4);
    CacheKey key;
    key.layoutVersion = uint32_t(header.number(4));
    key.kind = header.text();
    key.parameters = header.text();
    if (!header.ok()) return std::nullopt;
    return key;
}

void CacheDir::removeOrphanedTemporaries(const std::string& name) const {
    // AtomicFile names its temporary ".<stem>.tmp-<pid>-<n><ext>": remove those whose writer is gone.
    const std::string stem = std::filesystem::path(name).stem().string();
    const std::string prefix = "." + stem + ".tmp-";
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(dir_, ec)) {
        std::string file = entry.path().filename().string();
        if (file.rfind(prefix, 0) != 0) continue;
        long pid = std::strtol(file.c_str() + prefix.size(), nullptr, 10);
        if (!processAlive(pid)) std::filesystem::remove(entry.path(), ec);
    }
}

size_t CacheDir::pruneLeastRecentlyUsed(const std::string& prefix, const std::string& extension, size_t keep) const {
    std::error_code ec;
    std::vector<std::pair<std::filesystem::file_time_type, std::filesystem::path>> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir_, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(prefix, 0) != 0 || entry.path().extension() != extension) continue;
        std::error_code timeError;
        auto time = entry.last_write_time(timeError);
        if (!timeError) files.emplace_back(time, entry.path());
    }
    if (files.size() <= keep) return 0;
    std::sort(files.begin(), files.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    size_t removed = 0;
    for (size_t i = keep; i < files.size(); ++i) removed += std::filesystem::remove(files[i].second, ec) ? 1 : 0;
    return removed;
}

bool CacheDir::store(const std::string& name, const CacheKey& key, std::string_view payload) const {
    static std::mutex mutex;
    static std::set<std::string> reported;
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    try {
        if (ec) throw Error(dir_.string() + ": cannot create the folder (" + ec.message() + ")");
        removeOrphanedTemporaries(name);
        writeFileAtomically(dir_ / name, encodeCacheFile(key, payload), "cache");
        return true;
    } catch (const Error& e) {
        std::lock_guard<std::mutex> lock(mutex);
        if (reported.insert(dir_.string()).second)
            log::warn(e.what(), "; results are not cached (set GLIMMER_CACHE_DIR to a writable folder)");
        return false;
    }
}

}  // namespace glimmer::cache
