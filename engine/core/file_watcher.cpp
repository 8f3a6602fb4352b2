#include "core/file_watcher.h"

#include <sys/inotify.h>
#include <unistd.h>

#include <cerrno>

#include "core/error.h"
#include "core/log.h"

namespace glimmer {
namespace fs = std::filesystem;

// How often the modification-time fallback walks the tree (a small shader folder: microseconds per walk).
static constexpr std::chrono::milliseconds kScanInterval{100};

FileWatcher::FileWatcher(fs::path root, std::chrono::milliseconds debounce, Mode preferred, bool recursive)
    : debounce_(debounce), mode_(preferred), recursive_(recursive) {
    std::error_code ec;
    root_ = fs::weakly_canonical(root, ec);
    if (ec || !fs::is_directory(root_)) throw Error(root.string() + ": cannot watch: not a directory");
    if (mode_ == Mode::Inotify) {
        inotify_ = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
        if (inotify_ < 0) {
            log::warn("file watcher: inotify unavailable (errno ", errno, "), comparing modification times");
            mode_ = Mode::ModificationTime;
        } else {
            addWatches(root_);
        }
    }
    if (mode_ == Mode::ModificationTime) scanModificationTimes(false);
}

FileWatcher::~FileWatcher() {
    if (inotify_ >= 0) close(inotify_);
}

void FileWatcher::addWatches(const fs::path& folder) {
    auto add = [&](const fs::path& dir) {
        int wd = inotify_add_watch(inotify_, dir.c_str(), IN_CLOSE_WRITE | IN_MOVED_TO | IN_CREATE);
        if (wd < 0) {
            log::warn("file watcher: cannot watch ", dir.string(), " (errno ", errno, "), comparing modification times");
            mode_ = Mode::ModificationTime;
            scanModificationTimes(false);
            return false;
        }
        watchFolders_[wd] = dir;
        return true;
    };
    if (!add(folder) || !recursive_) return;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(folder, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec))
        if (it->is_directory() && !add(it->path())) return;
}

void FileWatcher::noteChange(const fs::path& file) {
    pending_.insert(file);
    lastEvent_ = Clock::now();
}

void FileWatcher::readInotify() {
    alignas(inotify_event) char buffer[16 * 1024];
    for (;;) {
        ssize_t length = read(inotify_, buffer, sizeof buffer);
        if (length <= 0) break;  // EAGAIN: nothing more for now
        for (ssize_t offset = 0; offset < length;) {
            const auto* event = reinterpret_cast<const inotify_event*>(buffer + offset);
            offset += ssize_t(sizeof(inotify_event) + event->len);
            auto folder = watchFolders_.find(event->wd);
            if (folder == watchFolders_.end() || event->len == 0) continue;
            fs::path path = folder->second / event->name;
            if (event->mask & IN_ISDIR) {
                if (recursive_ && event->mask & (IN_CREATE | IN_MOVED_TO)) addWatches(path);
                continue;
            }
            // IN_CREATE alone is an empty new file; its content arrives with IN_CLOSE_WRITE.
            if (event->mask & (IN_CLOSE_WRITE | IN_MOVED_TO)) noteChange(path);
        }
    }
}

void FileWatcher::scanModificationTimes(bool record) {
    std::error_code ec;
    std::map<fs::path, fs::file_time_type> now;
    for (auto it = fs::recursive_directory_iterator(root_, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
        if (!recursive_ && it.depth() == 0 && it->is_directory()) it.disable_recursion_pending();
        if (!it->is_regular_file()) continue;
        std::error_code timeError;
        auto time = fs::last_write_time(it->path(), timeError);
        if (timeError) continue;
        now[it->path()] = time;
        auto old = mtimes_.find(it->path());
        if (record && (old == mtimes_.end() || old->second != time)) noteChange(it->path());
    }
    mtimes_ = std::move(now);
    lastScan_ = Clock::now();
}

std::vector<fs::path> FileWatcher::poll() {
    if (mode_ == Mode::Inotify) readInotify();
    if (mode_ == Mode::ModificationTime && Clock::now() - lastScan_ >= kScanInterval) scanModificationTimes(true);
    std::vector<fs::path> changed;
    if (pending_.empty() || Clock::now() - lastEvent_ < debounce_) return changed;
    for (const fs::path& p : pending_) {
        std::error_code ec;
        fs::path canonical = fs::weakly_canonical(p, ec);
        changed.push_back(ec ? p : canonical);
    }
    pending_.clear();
    return changed;
}

}  // namespace glimmer
