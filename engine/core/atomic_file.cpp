#include "core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace glimmer {

namespace {

std::string prefix(const std::string& flag, const std::filesystem::path& path) {
    return (flag.empty() ? "" : flag + ": ") + path.string() + ": ";
}

}  // namespace

void checkOutputPath(const std::filesystem::path& path, const std::string& flag) {
    std::error_code ec;
    std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    std::filesystem::path parent = absolute.parent_path();
    if (path.filename().empty()) throw Error(prefix(flag, path) + "names a folder, not a file");
    if (!std::filesystem::is_directory(parent, ec))
        throw Error(prefix(flag, path) + "directory " + parent.string() + " does not exist");
    std::filesystem::file_status status = std::filesystem::status(absolute, ec);
    if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
        throw Error(prefix(flag, path) + "exists and is not a regular file (a FIFO, device or folder is not replaced)");
    // Create (and remove) a probe file: access() says yes to root everywhere, even in /proc.
    std::filesystem::path probe = parent / (".glimmer-probe-" + std::to_string(getpid()));
    int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) throw Error(prefix(flag, path) + "cannot write in " + parent.string() + " (" + std::strerror(errno) + ")");
    ::close(fd);
    ::unlink(probe.c_str());
}

void createOutputFolder(const std::filesystem::path& path, const std::string& flag) {
    std::error_code ec;
    std::filesystem::path parent = std::filesystem::absolute(path, ec).parent_path();
    if (ec || std::filesystem::is_directory(parent, ec)) return;
    std::filesystem::create_directories(parent, ec);
    if (ec) throw Error(prefix(flag, path) + "cannot create folder " + parent.string() + " (" + ec.message() + ")");
}

AtomicFile::AtomicFile(std::filesystem::path target, std::string flag) : target_(std::move(target)), flag_(std::move(flag)) {
    checkOutputPath(target_, flag_);
    static std::atomic<unsigned> counter{0};
    std::filesystem::path absolute = std::filesystem::absolute(target_);
    // The extension stays last so writers that pick a format by name still see it.
    std::string name = "." + absolute.stem().string() + ".tmp-" + std::to_string(getpid()) + "-" +
                       std::to_string(counter++) + absolute.extension().string();
    temp_ = absolute.parent_path() / name;
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd_ < 0) throw Error(prefix(flag_, target_) + "cannot create a temporary file (" + std::strerror(errno) + ")");
}

AtomicFile::~AtomicFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_) ::unlink(temp_.c_str());
}

void AtomicFile::fail(const std::string& what) const { throw Error(prefix(flag_, target_) + what); }

void AtomicFile::write(const void* data, size_t size) {
    const char* p = static_cast<const char*>(data);
    while (size > 0) {
        ssize_t n = ::write(fd_, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) fail(std::string("write failed (") + (n < 0 ? std::strerror(errno) : "no space") + ")");
        p += n;
        size -= size_t(n);
    }
}

void AtomicFile::commit() {
    if (::fsync(fd_) != 0) fail(std::string("write failed (") + std::strerror(errno) + ")");
    int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail(std::string("write failed (") + std::strerror(errno) + ")");
    if (std::rename(temp_.c_str(), target_.c_str()) != 0)
        fail(std::string("cannot replace the file (") + std::strerror(errno) + ")");
    committed_ = true;
    // Make the rename itself durable (best effort: some file systems refuse fsync on folders).
    int dir = ::open(temp_.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir >= 0) {
        ::fsync(dir);
        ::close(dir);
    }
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes, const std::string& flag) {
    AtomicFile file(path, flag);
    file.write(bytes);
    file.commit();
}

}  // namespace glimmer
