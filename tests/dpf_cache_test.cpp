// The wang2020 DPF tables' disk cache (core/cache_file.h): a cache file with the right header but NaN, 1e30, -1
// or all-zero values, or with a wrong checksum, is regenerated (the tables equal freshly generated ones); an
// unwritable cache folder is not claimed as cached.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/cache_file.h"
#include "glints/wang2020/wang2020_dpf.h"

namespace fs = std::filesystem;
namespace w = glimmer::wang2020;

namespace {

const w::DpfResolution kRes{6, 6, 12};  // small: generation takes milliseconds

fs::path freshDir(const std::string& name) {
    fs::path dir = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "dpf-cache" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void expectSameTables(const w::DpfSet& a, const w::DpfSet& b) {
    ASSERT_EQ(a.tables.size(), b.tables.size());
    for (size_t k = 0; k < a.tables.size(); ++k) EXPECT_EQ(a.tables[k].values, b.tables[k].values) << "table " << k;
}

TEST(Wang2020DpfCache, SecondLoadComesFromTheCache) {
    fs::path dir = freshDir("roundtrip");
    w::DpfSet fresh = w::loadOrGenerateDpfSet(kRes, dir, 2);
    EXPECT_FALSE(fresh.fromCache);
    w::DpfSet cached = w::loadOrGenerateDpfSet(kRes, dir, 2);
    EXPECT_TRUE(cached.fromCache);
    expectSameTables(fresh, cached);
}

TEST(Wang2020DpfCache, WrongValuesWithAValidHeaderAreRegenerated) {
    fs::path dir = freshDir("values");
    w::DpfSet fresh = w::loadOrGenerateDpfSet(kRes, dir, 2);
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), 1e30f, -1.0f, 0.0f}) {
        // Rewrite every table with a correct header and checksum around the bad values: only the value check
        // can catch them.
        std::vector<float> values(kRes.size(), bad);
        std::string payload(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
        int rewritten = 0;
        for (const auto& entry : fs::directory_iterator(dir)) {
            std::optional<glimmer::cache::CacheKey> key = glimmer::cache::readCacheKey(entry.path());
            ASSERT_TRUE(key) << entry.path();
            std::ofstream(entry.path(), std::ios::binary | std::ios::trunc) << glimmer::cache::encodeCacheFile(*key, payload);
            ++rewritten;
        }
        EXPECT_EQ(rewritten, int(w::kRoughnessSamples.size()));
        w::DpfSet again = w::loadOrGenerateDpfSet(kRes, dir, 2);
        EXPECT_FALSE(again.fromCache) << "value " << bad << " was trusted";
        expectSameTables(fresh, again);
    }
}

TEST(Wang2020DpfCache, UnwritableFolderIsNotClaimedAsCached) {
    fs::path dir = freshDir("unwritable");
    std::ofstream(dir / "file") << "x";
    w::DpfSet first = w::loadOrGenerateDpfSet(kRes, dir / "file" / "cache", 2);
    w::DpfSet second = w::loadOrGenerateDpfSet(kRes, dir / "file" / "cache", 2);
    EXPECT_FALSE(first.fromCache);
    EXPECT_FALSE(second.fromCache);
    expectSameTables(first, second);
}

}  // namespace
