// Output files and caches (core/atomic_file.h, core/cache_file.h), without GL: a failed write exits with an
// error naming the file and leaves nothing half-written; caches are trusted only with matching headers,
// checksums and values.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/atomic_file.h"
#include "core/cache_file.h"
#include "core/error.h"
#include "core/image_io.h"

namespace fs = std::filesystem;

namespace {

fs::path freshDir(const std::string& name) {
    fs::path dir = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "output-files" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string readAll(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

size_t filesIn(const fs::path& dir) {
    size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++n;
    return n;
}

// Writes larger than `bytes` fail with EFBIG (SIGXFSZ ignored) while this object lives: a full disk, in process.
class FileSizeLimit {
public:
    explicit FileSizeLimit(rlim_t bytes) {
        getrlimit(RLIMIT_FSIZE, &saved_);
        previous_ = signal(SIGXFSZ, SIG_IGN);
        rlimit limit = saved_;
        limit.rlim_cur = bytes;
        setrlimit(RLIMIT_FSIZE, &limit);
    }
    ~FileSizeLimit() {
        setrlimit(RLIMIT_FSIZE, &saved_);
        signal(SIGXFSZ, previous_);
    }

private:
    rlimit saved_{};
    void (*previous_)(int) = nullptr;
};

TEST(AtomicFile, FailedWriteKeepsTheOldFileAndLeavesNoTemporary) {
    fs::path dir = freshDir("full");
    fs::path target = dir / "report.json";
    glimmer::writeFileAtomically(target, "old", "--json");
    std::string big(1 << 20, 'x');
    {
        FileSizeLimit limit(64 * 1024);
        try {
            glimmer::writeFileAtomically(target, big, "--json");
            ADD_FAILURE() << "a write past the file size limit succeeded";
        } catch (const glimmer::Error& e) {
            EXPECT_NE(std::string(e.what()).find("--json: " + target.string()), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(readAll(target), "old");
    EXPECT_EQ(filesIn(dir), 1u) << "a temporary file was left behind";
    glimmer::writeFileAtomically(target, big, "--json");
    EXPECT_EQ(readAll(target), big);
}

TEST(AtomicFile, FailedImageWriteLeavesNoFile) {
    fs::path dir = freshDir("image");
    std::vector<float> pixels(256 * 256 * 4, 0.5f);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = float(i % 977) / 977.0f;  // not compressible to nothing
    for (const char* name : {"a.exr", "a.png"}) {
        FileSizeLimit limit(4096);
        std::vector<uint8_t> bytes(pixels.size());
        for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t(pixels[i] * 255);
        if (std::string(name) == "a.exr") EXPECT_THROW(glimmer::writeExr(dir / name, pixels.data(), 256, 256), glimmer::Error);
        else EXPECT_THROW(glimmer::writePng(dir / name, bytes.data(), 256, 256), glimmer::Error);
    }
    EXPECT_EQ(filesIn(dir), 0u);
}

TEST(AtomicFile, FifosDevicesAndMissingFoldersAreRefusedUpFront) {
    fs::path dir = freshDir("special");
    ASSERT_EQ(mkfifo((dir / "pipe.png").c_str(), 0600), 0);
    EXPECT_THROW(glimmer::checkOutputPath(dir / "pipe.png", "--out"), glimmer::Error);
    EXPECT_THROW(glimmer::checkOutputPath("/dev/full", "--out"), glimmer::Error);
    EXPECT_THROW(glimmer::checkOutputPath(dir / "missing" / "a.png", "--out"), glimmer::Error);
    EXPECT_THROW(glimmer::checkOutputPath(dir, "--out"), glimmer::Error);
    std::vector<uint8_t> rgba(4 * 4 * 4, 255);
    EXPECT_THROW(glimmer::writePng(dir / "pipe.png", rgba.data(), 4, 4), glimmer::Error);  // does not block
    EXPECT_NO_THROW(glimmer::checkOutputPath(dir / "new.png", "--out"));
}

// render --out creates a missing folder (issue 39, 13); a file in the way is a one-line error naming the flag.
TEST(AtomicFile, OutputFolderIsCreatedUnlessAFileIsInTheWay) {
    fs::path dir = freshDir("out-folder");
    glimmer::createOutputFolder(dir / "a" / "b" / "x.png", "--out");
    EXPECT_TRUE(fs::is_directory(dir / "a" / "b"));
    EXPECT_NO_THROW(glimmer::checkOutputPath(dir / "a" / "b" / "x.png", "--out"));
    std::ofstream(dir / "file") << "x";
    try {
        glimmer::createOutputFolder(dir / "file" / "sub" / "x.png", "--out");
        ADD_FAILURE() << "no error";
    } catch (const glimmer::Error& e) {
        std::string message = e.what();
        EXPECT_EQ(message.rfind("--out: ", 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

glimmer::cache::CacheKey testKey(const std::string& parameters = "n=4") { return {"test-cache", 3, parameters}; }

TEST(CacheFile, RoundTripAndEveryMismatchIsRejected) {
    fs::path dir = freshDir("cache");
    glimmer::cache::CacheDir cache(dir);
    std::string payload = "0123456789abcdef";
    ASSERT_TRUE(cache.store("t.bin", testKey(), payload));
    EXPECT_EQ(cache.load("t.bin", testKey(), payload.size()).value_or(""), payload);
    EXPECT_FALSE(cache.load("t.bin", testKey("n=5"), payload.size()));                // other parameters
    EXPECT_FALSE(cache.load("t.bin", {"other-cache", 3, "n=4"}, payload.size()));     // other kind
    EXPECT_FALSE(cache.load("t.bin", {"test-cache", 4, "n=4"}, payload.size()));      // other layout
    EXPECT_FALSE(cache.load("t.bin", testKey(), payload.size() + 4));                 // other size
    EXPECT_FALSE(cache.load("t.bin", testKey(), 0, [](std::string_view) { return false; }));  // values rejected
    EXPECT_FALSE(cache.load("missing.bin", testKey()));

    std::string bytes = readAll(dir / "t.bin");
    std::string flipped = bytes;
    flipped.back() ^= 1;  // one payload bit
    std::ofstream(dir / "t.bin", std::ios::binary | std::ios::trunc) << flipped;
    EXPECT_FALSE(cache.load("t.bin", testKey(), payload.size()));
    std::ofstream(dir / "t.bin", std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() - 3);
    EXPECT_FALSE(cache.load("t.bin", testKey(), payload.size()));  // truncated (a killed non-atomic write)
    std::ofstream(dir / "t.bin", std::ios::binary | std::ios::trunc) << payload;
    EXPECT_FALSE(cache.load("t.bin", testKey(), payload.size()));  // an old headerless cache
    std::string header = bytes;
    header[20] ^= 1;
    std::ofstream(dir / "t.bin", std::ios::binary | std::ios::trunc) << header;
    EXPECT_FALSE(cache.load("t.bin", testKey(), payload.size()));
}

TEST(CacheFile, UnwritableFolderIsReportedAndNotClaimed) {
    fs::path dir = freshDir("unwritable");
    std::ofstream(dir / "file") << "x";
    glimmer::cache::CacheDir cache(dir / "file" / "sub");  // a folder below a regular file cannot exist
    EXPECT_FALSE(cache.store("t.bin", testKey(), "abc"));
    EXPECT_FALSE(cache.store("u.bin", testKey(), "abc"));
    EXPECT_FALSE(cache.load("t.bin", testKey()));
}

// Bounded caches (the environment's) drop the files no launch has read for the longest time: an entry written
// long ago but read at every start (the default scene's environment) survives newer writes of other maps.
TEST(CacheFile, PruningKeepsTheMostRecentlyReadFilesNotTheNewestWritten) {
    fs::path dir = freshDir("prune");
    glimmer::cache::CacheDir cache(dir);
    const auto now = fs::file_time_type::clock::now();
    for (int i = 0; i < 4; ++i) {
        std::string name = "env_" + std::to_string(i) + ".bin";
        ASSERT_TRUE(cache.store(name, testKey(), "abc"));
        fs::last_write_time(dir / name, now - std::chrono::hours(10 - i));   // env_0 written first
    }
    std::ofstream(dir / "other.bin") << "not an env file";
    fs::last_write_time(dir / "other.bin", now - std::chrono::hours(20));
    ASSERT_TRUE(cache.load("env_0.bin", testKey()));   // the oldest is read again
    EXPECT_EQ(cache.pruneLeastRecentlyUsed("env_", ".bin", 3), 1u);
    EXPECT_TRUE(fs::exists(dir / "env_0.bin"));
    EXPECT_FALSE(fs::exists(dir / "env_1.bin"));        // the least recently used
    EXPECT_TRUE(fs::exists(dir / "env_2.bin"));
    EXPECT_TRUE(fs::exists(dir / "env_3.bin"));
    EXPECT_TRUE(fs::exists(dir / "other.bin"));          // not matched by the prefix
    EXPECT_EQ(cache.pruneLeastRecentlyUsed("env_", ".bin", 3), 0u);
}

TEST(CacheFile, TemporariesOfDeadWritersAreRemovedAndNeverRead) {
    fs::path dir = freshDir("orphans");
    glimmer::cache::CacheDir cache(dir);
    // What a killed writer leaves: AtomicFile's temporary name with a pid that no longer exists.
    fs::path orphan = dir / ".t.tmp-2147483646-0.bin";
    std::ofstream(orphan) << glimmer::cache::encodeCacheFile(testKey(), "abc");
    EXPECT_FALSE(cache.load("t.bin", testKey()));
    ASSERT_TRUE(cache.store("t.bin", testKey(), "abc"));
    EXPECT_FALSE(fs::exists(orphan));
    EXPECT_EQ(filesIn(dir), 1u);
    auto key = glimmer::cache::readCacheKey(dir / "t.bin");
    ASSERT_TRUE(key);
    EXPECT_EQ(key->kind, "test-cache");
    EXPECT_EQ(key->parameters, "n=4");
    EXPECT_EQ(key->layoutVersion, 3u);
}

}  // namespace
