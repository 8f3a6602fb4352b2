// The environment precomputation's disk cache (environment/environment_cache.h): a second Environment reads what the
// first built, bit for bit; a damaged file, another image under the same path, or an edited shader is never
// trusted; the cache can be turned off.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/files.h"
#include "core/image_io.h"
#include "environment/environment.h"
#include "platform/context.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(EnvironmentCacheTest, GlContext);

namespace glimmer {
namespace {

namespace fs = std::filesystem;

// Points the cache at a fresh folder for one test and restores the variable after it.
class EnvironmentCacheTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        dir_ = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "environment_cache" / test;
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        if (const char* old = std::getenv("GLIMMER_CACHE_DIR")) saved_ = old;
        setenv("GLIMMER_CACHE_DIR", (dir_ / "cache").c_str(), 1);
        unsetenv("GLIMMER_ENV_CACHE");
        // A coarser prefilter quadrature (3.5x faster): these tests judge the cache, not the maps' accuracy
        // (tests/environment_test.cpp does, at the default), and build about ten environments.
        setenv("GLIMMER_ENV_PREFILTER_REFINE", "2", 1);
        context_ = createHeadlessContext(Backend::Egl);
    }
    void TearDown() override {
        context_.reset();
        unsetenv("GLIMMER_ENV_PREFILTER_REFINE");
        if (saved_.empty()) unsetenv("GLIMMER_CACHE_DIR");
        else setenv("GLIMMER_CACHE_DIR", saved_.c_str(), 1);
    }
    std::vector<fs::path> cacheFiles() const {
        std::vector<fs::path> files;
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(dir_ / "cache", ec))
            if (e.path().extension() == ".bin") files.push_back(e.path());
        return files;
    }
    fs::path writeMap(const std::string& name, float tint) const {
        ImageF image;
        image.width = 64;
        image.height = 32;
        image.channels = 3;
        image.pixels.resize(size_t(64) * 32 * 3);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 64; ++x)
                for (int c = 0; c < 3; ++c)
                    image.pixels[(size_t(y) * 64 + x) * 3 + c] = tint * (0.2f + 0.1f * c) + 4.0f * (x == 20 && y == 8);
        fs::path path = dir_ / name;
        writeImage(path, image);
        return path;
    }
    fs::path dir_;
    std::string saved_;
    std::unique_ptr<GLContext> context_;
};

std::vector<float> allLevels(GLuint texture, int levels, size_t level0Floats) {
    std::vector<float> all;
    for (int level = 0; level < levels; ++level) {
        size_t n = level0Floats >> (2 * level);
        size_t at = all.size();
        all.resize(at + n);
        glGetTextureImage(texture, level, GL_RGBA, GL_FLOAT, GLsizei(n * sizeof(float)), all.data() + at);
    }
    return all;
}

struct Maps {
    std::vector<float> source, specular, rungs, lut;
    std::array<glm::vec3, 9> sh;
};

Maps readMaps(const Environment& env) {
    const size_t face = size_t(Environment::kFaceSize) * Environment::kFaceSize * 4;
    Maps m;
    m.source = allLevels(env.sourceCube(), 9, face * 6);
    m.specular = allLevels(env.specularCubeArray(), 1, face * 12);
    m.rungs = allLevels(env.specularFineArray(), Environment::kFineLevels,
                        (face / 4) * 12 * Environment::kSublevels);
    m.lut.resize(size_t(Environment::kBrdfLutSize) * Environment::kBrdfLutSize * 4);
    glGetTextureImage(env.brdfLut(), 0, GL_RGBA, GL_FLOAT, GLsizei(m.lut.size() * sizeof(float)), m.lut.data());
    m.sh = env.irradianceSh();
    return m;
}

void expectSameMaps(const Maps& a, const Maps& b) {
    EXPECT_TRUE(a.source == b.source) << "source cube differs";
    EXPECT_TRUE(a.specular == b.specular) << "mirror level differs";
    EXPECT_TRUE(a.rungs == b.rungs) << "prefiltered rungs differ";
    EXPECT_TRUE(a.lut == b.lut) << "BRDF table differs";
    for (int i = 0; i < 9; ++i) EXPECT_EQ(a.sh[i], b.sh[i]) << "SH " << i;
}

TEST_F(EnvironmentCacheTest, SecondLaunchReadsTheSameMapsFromTheCache) {
    fs::path map = writeMap("map.exr", 1.0f);
    Maps built;
    {
        Environment env(defaultShaderDir());
        env.update(map.string(), SunDescription{}, "--env");
        EXPECT_FALSE(env.timings().cacheHit);
        EXPECT_TRUE(env.timings().cacheStored);
        built = readMaps(env);
    }
    ASSERT_EQ(cacheFiles().size(), 1u);
    Environment env(defaultShaderDir());
    env.update(map.string(), SunDescription{}, "--env");
    EXPECT_TRUE(env.timings().cacheHit);
    EXPECT_EQ(env.timings().prefilterMs, 0.0);   // nothing was recomputed
    expectSameMaps(built, readMaps(env));
    EXPECT_EQ(env.stats()["cache"]["hit"], true);

    // The procedural sky is cached per sun: another sun is another file, not a stale read.
    Environment sky(defaultShaderDir());
    sky.update("", SunDescription{}, "--env");
    SunDescription other;
    other.direction = glm::normalize(glm::vec3(-0.5f, 0.4f, 0.2f));
    Environment sky2(defaultShaderDir());
    sky2.update("", other, "--env");
    EXPECT_FALSE(sky2.timings().cacheHit);
    EXPECT_EQ(cacheFiles().size(), 3u);
}

TEST_F(EnvironmentCacheTest, DamagedFileOrReplacedImageIsRebuiltNotTrusted) {
    fs::path map = writeMap("map.exr", 1.0f);
    Maps built;
    {
        Environment env(defaultShaderDir());
        env.update(map.string(), SunDescription{}, "--env");
        built = readMaps(env);
    }
    ASSERT_EQ(cacheFiles().size(), 1u);
    fs::path file = cacheFiles()[0];
    {   // one flipped byte in the payload
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(-1000, std::ios::end);
        char c = 0;
        f.read(&c, 1);
        f.seekp(-1000, std::ios::end);
        c = char(c ^ 0x40);
        f.write(&c, 1);
    }
    {
        Environment env(defaultShaderDir());
        env.update(map.string(), SunDescription{}, "--env");
        EXPECT_FALSE(env.timings().cacheHit);
        expectSameMaps(built, readMaps(env));
    }
    fs::resize_file(file, fs::file_size(file) / 2);   // a killed writer cannot leave this (atomic), a disk can
    {
        Environment env(defaultShaderDir());
        env.update(map.string(), SunDescription{}, "--env");
        EXPECT_FALSE(env.timings().cacheHit);
        expectSameMaps(built, readMaps(env));
    }
    // Another image under the same path: keyed by the bytes, so it is built, and its maps differ.
    writeMap("map.exr", 2.0f);
    Environment env(defaultShaderDir());
    env.update(map.string(), SunDescription{}, "--env");
    EXPECT_FALSE(env.timings().cacheHit);
    EXPECT_FALSE(readMaps(env).source == built.source);
}

TEST_F(EnvironmentCacheTest, EditedShaderOrDisabledCacheIsNotRead) {
    fs::path map = writeMap("map.exr", 1.0f);
    {
        Environment env(defaultShaderDir());
        env.update(map.string(), SunDescription{}, "--env");
        ASSERT_TRUE(env.timings().cacheStored);
    }
    // A copy of the shader folder whose prefilter differs by a comment: another key.
    fs::path shaders = dir_ / "shaders";
    fs::copy(defaultShaderDir(), shaders, fs::copy_options::recursive);
    const fs::path prefilter = shaders / "environment" / "prefilter.comp";
    ASSERT_TRUE(fs::exists(prefilter)) << prefilter;   // a moved shader must not make this edit a silent no-op
    std::ofstream(prefilter, std::ios::app) << "\n// edited\n";
    {
        Environment env(shaders);
        env.update(map.string(), SunDescription{}, "--env");
        EXPECT_FALSE(env.timings().cacheHit);
    }
    EXPECT_EQ(cacheFiles().size(), 2u);
    // Another prefilter quadrature is another key.
    setenv("GLIMMER_ENV_PREFILTER_REFINE", "3", 1);
    {
        Environment env(defaultShaderDir());
        env.update(map.string(), SunDescription{}, "--env");
        EXPECT_FALSE(env.timings().cacheHit);
    }
    setenv("GLIMMER_ENV_PREFILTER_REFINE", "2", 1);
    EXPECT_EQ(cacheFiles().size(), 3u);
    setenv("GLIMMER_ENV_CACHE", "0", 1);
    Environment env(defaultShaderDir());
    env.update(map.string(), SunDescription{}, "--env");
    EXPECT_FALSE(env.timings().cacheHit);
    EXPECT_FALSE(env.timings().cacheStored);
    unsetenv("GLIMMER_ENV_CACHE");
}

}  // namespace
}  // namespace glimmer
