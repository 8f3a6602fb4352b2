// Output files that are either complete or absent. Every writer of the engine (images, bench reports, caches)
// goes through here: the bytes go to a temporary file in the target's own folder (same file system, so the
// rename is atomic), which is flushed, fsync'ed, checked and only then renamed over the target. A failed or
// interrupted write leaves the target as it was (an existing file is replaced only by a complete one), and the
// temporary file is removed on failure. A killed process can leave a temporary file behind; it is named
// ".<target>.tmp-<pid>-<n>" so no reader mistakes it for the target.
#pragma once
#include <filesystem>
#include <string>
#include <string_view>

namespace glimmer {

// Throws Error("<flag>: <path>: ...") unless `path` can be created or replaced: its folder exists and the
// target, when present, is a regular file (a FIFO, a device such as /dev/full, or a folder is refused, so
// nothing blocks or writes into a device). `flag` names the option the path came from ("--out").
void checkOutputPath(const std::filesystem::path& path, const std::string& flag);
// Creates the folder `path` will be written in when it is missing (render --out): Error("<flag>: <path>: cannot
// create folder ...") when that fails (a file in the way, no permission).
void createOutputFolder(const std::filesystem::path& path, const std::string& flag);

class AtomicFile {
public:
    // Creates the temporary file next to `target` (after checkOutputPath). `flag` prefixes error messages.
    AtomicFile(std::filesystem::path target, std::string flag);
    ~AtomicFile();  // removes the temporary file unless commit() succeeded
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    // Appends bytes; throws Error naming the target on a short write (full disk, file size limit).
    void write(const void* data, size_t size);
    void write(std::string_view text) { write(text.data(), text.size()); }
    // Flushes to disk, checks, closes and renames over the target. Throws Error naming the target on failure.
    void commit();

    [[noreturn]] void fail(const std::string& what) const;

private:
    std::filesystem::path target_, temp_;
    std::string flag_;
    int fd_ = -1;
    bool committed_ = false;
};

// Writes `bytes` to `path` atomically (AtomicFile). Throws Error naming `flag` and the path.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes, const std::string& flag);

}  // namespace glimmer
