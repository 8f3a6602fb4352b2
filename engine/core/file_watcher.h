// Watches a folder tree for changed files (shader hot reload). Linux inotify (IN_CLOSE_WRITE | IN_MOVED_TO:
// editors that save by renaming a temporary file are seen too), non-blocking, polled from the frame loop; when
// inotify is unavailable, or a folder cannot be watched, modification times are compared instead. Changes are
// reported once no further event arrived for `debounce` (an editor's several writes give one reload).
#pragma once
#include <chrono>
#include <filesystem>
#include <map>
#include <set>
#include <vector>

namespace glimmer {

class FileWatcher {
public:
    using Clock = std::chrono::steady_clock;
    enum class Mode { Inotify, ModificationTime };

    // recursive = false watches the files of `root` only (a user method's folder, which may be any folder).
    explicit FileWatcher(std::filesystem::path root, std::chrono::milliseconds debounce = std::chrono::milliseconds(60),
                         Mode preferred = Mode::Inotify, bool recursive = true);
    ~FileWatcher();
    FileWatcher(const FileWatcher&) = delete;
    FileWatcher& operator=(const FileWatcher&) = delete;

    // Files (canonical paths) changed since the last report, once the debounce interval has passed.
    std::vector<std::filesystem::path> poll();
    Mode mode() const { return mode_; }
    const std::filesystem::path& root() const { return root_; }

private:
    void addWatches(const std::filesystem::path& folder);
    void readInotify();
    void scanModificationTimes(bool record);
    void noteChange(const std::filesystem::path& file);

    std::filesystem::path root_;
    std::chrono::milliseconds debounce_;
    Mode mode_;
    bool recursive_ = true;
    int inotify_ = -1;
    std::map<int, std::filesystem::path> watchFolders_;
    std::map<std::filesystem::path, std::filesystem::file_time_type> mtimes_;
    Clock::time_point lastScan_{}, lastEvent_{};
    std::set<std::filesystem::path> pending_;
};

}  // namespace glimmer
