#include "core/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "core/error.h"

namespace glimmer {

namespace {

// Opens without blocking (O_NONBLOCK: a FIFO with no writer would block a plain open), checks what the descriptor
// is, then reads at most kind.maxBytes + 1 bytes into `out` through `grow`, which resizes the buffer.
template <class Buffer>
void readChecked(const std::filesystem::path& path, const InputFileKind& kind, Buffer& out) {
    const std::string name = path.string() + ": " + kind.what;
    int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        int error = errno;
        if (error == ENOENT) throw Error(name + " not found");
        throw Error(name + " cannot be opened (" + std::strerror(error) + ")");
    }
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat info {};
    if (::fstat(fd, &info) != 0) throw Error(name + " cannot be read (" + std::strerror(errno) + ")");
    if (S_ISDIR(info.st_mode)) throw Error(name + " is a folder, not a file");
    if (!S_ISREG(info.st_mode)) throw Error(name + " is not a regular file (a FIFO, device or socket is not read)");
    const uint64_t size = uint64_t(info.st_size);
    if (size > kind.maxBytes)
        throw Error(name + " has " + std::to_string(size) + " bytes, over the limit of " + byteSizeText(kind.maxBytes));
    out.resize(size_t(size));
    size_t got = 0;
    // Read until end of file; a file that grows past the limit while it is read is refused as well.
    for (;;) {
        if (got == out.size()) {
            if (uint64_t(out.size()) > kind.maxBytes)
                throw Error(name + " grew past the limit of " + byteSizeText(kind.maxBytes) + " while it was read");
            out.resize(std::min<size_t>(size_t(kind.maxBytes) + 1, out.size() + 65536));
        }
        ssize_t n = ::read(fd, reinterpret_cast<char*>(out.data()) + got, out.size() - got);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw Error(name + " cannot be read (" + std::strerror(errno) + ")");
        }
        if (n == 0) break;
        got += size_t(n);
    }
    out.resize(got);
}

}  // namespace

std::string readInputFile(const std::filesystem::path& path, const InputFileKind& kind) {
    std::string text;
    readChecked(path, kind, text);
    return text;
}

void readInputFile(const std::filesystem::path& path, const InputFileKind& kind, std::vector<unsigned char>& bytes) {
    readChecked(path, kind, bytes);
}

std::string byteSizeText(uint64_t bytes) {
    if (bytes >= (uint64_t(1) << 30) && bytes % (uint64_t(1) << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
    if (bytes >= (uint64_t(1) << 20) && bytes % (uint64_t(1) << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
    if (bytes >= (uint64_t(1) << 10) && bytes % (uint64_t(1) << 10) == 0) return std::to_string(bytes >> 10) + " KiB";
    return std::to_string(bytes) + " bytes";
}

std::string displayPath(const std::filesystem::path& path) {
    std::error_code ec;
    std::filesystem::path relative = std::filesystem::relative(path, std::filesystem::current_path(ec), ec);
    if (ec || relative.empty() || *relative.begin() == "..") return path.string();
    return relative.string();
}

// $variable, else beside the running executable (an installed <prefix>/bin/glimmer finds
// <prefix>/share/glimmer/<name>; a copied folder may hold <name> next to the executable), else the source tree
// the build was configured from.
static std::filesystem::path dirFromEnvOr(const char* variable, const char* name) {
    if (const char* value = std::getenv(variable); value && *value) return value;
    std::error_code ec;
    std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        std::filesystem::path exeDir = exe.parent_path();
        for (const std::filesystem::path& candidate : {exeDir / ".." / "share" / "glimmer" / name, exeDir / name})
            if (std::filesystem::is_directory(candidate, ec)) return candidate.lexically_normal();
    }
    return std::filesystem::path(GLIMMER_SOURCE_DIR) / name;
}

std::filesystem::path defaultShaderDir() { return dirFromEnvOr("GLIMMER_SHADER_DIR", "shaders"); }
std::filesystem::path defaultContentDir() { return dirFromEnvOr("GLIMMER_CONTENT_DIR", "content"); }

}  // namespace glimmer
