// Chermain et al. 2020 / 2021 (shaders/glints/chermain2020/, engine/glints/chermain2020/): the dictionary against
// the distributions it encodes, its cache and texture, the number of lobes per grid cell, convergence to the smooth
// NDF, the 2021 anti-aliasing and LEAN mapping, golden images.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <regex>
#include <sstream>

#include "core/cache_file.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/files.h"
#include "glints/chermain2020/dictionary.h"
#include "glints/chermain2020/resources.h"
#include "glints/method_checks.h"
#include "glints/method_probe.h"
#include "platform/context.h"
#include "render/aov.h"
#include "render/offscreen.h"
#include "scene/builtin_scenes.h"
#include "support/golden.h"
#include "support/process.h"

using namespace glimmer;
namespace ch = glimmer::chermain2020;
namespace fs = std::filesystem;

namespace {

// A small dictionary (8 levels, 8 marginals) for the tests that generate: milliseconds instead of seconds.
ch::DictionarySpec smallSpec() {
    ch::DictionarySpec spec;
    spec.levels = 8;
    spec.marginals = 8;
    return spec;
}

// The definition of level l of marginal m, evaluated directly (all 2^(l+1) lobes, untruncated): the mixture
// 1 / 2^(l+1) sum_k [g(x - mu_k) + g(x + mu_k)] of the first 2^l means.
double mixture(const ch::DictionarySpec& spec, const std::vector<double>& means, int level, double x) {
    const size_t count = size_t(1) << level;
    double sum = 0.0;
    for (size_t k = 0; k < count; ++k)
        for (double c : {means[k], -means[k]}) {
            double d = (x - c) / spec.lobeStd;
            sum += std::exp(-0.5 * d * d);
        }
    return sum / (double(2 * count) * spec.lobeStd * std::sqrt(2.0 * M_PI));
}

// Moments of a tabulated marginal, as the GPU reconstructs it (midpoint rule over the texel centres, both signs).
double tableMoment(const ch::Dictionary& d, int level, int m, int power) {
    const float* v = d.marginal(level, m);
    double sum = 0.0;
    for (int j = 0; j < d.spec.resolution; ++j) sum += std::pow(d.spec.texelCentre(j), power) * v[j];
    return 2.0 * d.spec.texelWidth() * sum;
}

const ch::Dictionary& defaultDictionary() { return Chermain2020Resources::dictionary().dictionary; }

}  // namespace

// Sec. 5: level l of every marginal is the mixture of exactly 2^(l+1) Gaussian lobes (2^l means and their mirror
// twins): the table divided by the mixture evaluated here from the same means is one constant per marginal and
// level (the normalization; 1e-5 relative), and that constant is 1 within 0.2 %: the raw mixture already integrates
// to 1 over the table's range (the truncation at 4 sigma_dict and the texel sampling lose that little). Using any
// other number of means, or levels in the other order, breaks the constant ratio.
TEST(Chermain2020Dictionary, LevelsAreMixturesOfTwoToTheLevelPlusOneLobes) {
    const ch::DictionarySpec spec = smallSpec();
    const ch::Dictionary d = ch::generateDictionary(spec, 2);
    ASSERT_EQ(d.values.size(), spec.valueCount());
    for (int m = 0; m < spec.marginals; ++m) {
        std::vector<double> means = ch::lobeMeans(spec, m);
        ASSERT_EQ(means.size(), size_t(1) << (spec.levels - 1));
        for (int level = 0; level < spec.levels; ++level) {
            double rawIntegral = 0.0;
            std::vector<double> ratio;
            for (int j = 0; j < spec.resolution; ++j) {
                double exact = mixture(spec, means, level, spec.texelCentre(j));
                rawIntegral += 2.0 * spec.texelWidth() * exact;
                if (exact > 1e-3) ratio.push_back(d.at(level, m, j) / exact);
            }
            ASSERT_FALSE(ratio.empty());
            for (double r : ratio) ASSERT_NEAR(r / ratio.front(), 1.0, 1e-5) << "marginal " << m << " level " << level;
            EXPECT_NEAR(ratio.front(), 1.0 / rawIntegral, 1e-5 * ratio.front());
            EXPECT_NEAR(rawIntegral, 1.0, 2e-3) << "marginal " << m << " level " << level;
            EXPECT_NEAR(d.integral(level, m), 1.0, 1e-5);
        }
    }
}

// Sec. 5: the marginals encode the Beckmann marginal N(0, sigma_dict^2) of the dictionary's roughness. Each
// tabulated level's second moment is its own mixture's (the definition sampled at the texel centres over the
// table's range: 1e-4 relative), and averaged over the 192 marginals it is sigma_dict^2 within 5 standard errors
// of that mean (2 sigma^4 / (192 2^l) variance per level: 10 % at level 0, 0.06 % at level 15) plus the 0.1 % the
// truncation at 4 sigma_dict removes; the level with 2^15 means also has the Gaussian's fourth moment 3 sigma_dict^4
// (3 %).
TEST(Chermain2020Dictionary, MomentsAreTheBeckmannMarginals) {
    const ch::Dictionary& d = defaultDictionary();
    const ch::DictionarySpec& spec = d.spec;
    const double s2 = spec.sigmaDict() * spec.sigmaDict();
    std::vector<std::vector<double>> allMeans;
    for (int m = 0; m < spec.marginals; ++m) allMeans.push_back(ch::lobeMeans(spec, m));
    for (int level = 0; level < spec.levels; ++level) {
        double meanSecond = 0.0;
        for (int m = 0; m < spec.marginals; ++m) {
            double second = tableMoment(d, level, m, 2);
            if (level <= 6 || m % 48 == 0) {   // the definition costs 2^(l+1) exp per texel: sample the big levels
                const std::vector<double>& means = allMeans[size_t(m)];
                double mass = 0.0, moment = 0.0;
                for (int j = 0; j < spec.resolution; ++j) {
                    double x = spec.texelCentre(j), v = mixture(spec, means, level, x);
                    mass += v;
                    moment += x * x * v;
                }
                ASSERT_NEAR(second, moment / mass, 1e-4 * second) << "marginal " << m << " level " << level;
            }
            EXPECT_NEAR(tableMoment(d, level, m, 0), 1.0, 1e-3);
            meanSecond += second / spec.marginals;
        }
        double standardError = s2 * std::sqrt(2.0 / (double(spec.marginals) * double(size_t(1) << level)));
        std::printf("level %2d: mean second moment / sigma_dict^2 = %.5f (standard error %.5f)\n", level,
                    meanSecond / s2, standardError / s2);
        EXPECT_NEAR(meanSecond, s2, 5.0 * standardError + 0.002 * s2) << "level " << level;
    }
    double fourth = 0.0;
    for (int m = 0; m < spec.marginals; ++m) fourth += tableMoment(d, spec.levels - 1, m, 4) / spec.marginals;
    EXPECT_NEAR(fourth, 3.0 * s2 * s2, 0.03 * 3.0 * s2 * s2);
}

// The generator is deterministic (same spec: bit-identical tables on 1 or 2 threads) and the seed matters.
TEST(Chermain2020Dictionary, DeterministicForItsSpec) {
    ch::DictionarySpec spec = smallSpec();
    ch::Dictionary a = ch::generateDictionary(spec, 1), b = ch::generateDictionary(spec, 2);
    EXPECT_EQ(0, std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(float)));
    spec.seed += 1;
    ch::Dictionary c = ch::generateDictionary(spec, 2);
    EXPECT_NE(0, std::memcmp(a.values.data(), c.values.data(), a.values.size() * sizeof(float)));
}

// core/cache_file.h rules for the dictionary: the first load generates and stores, the second reads the same
// values back; a corrupted payload (checksum) or a payload whose values are wrong (right checksum, a marginal that
// is not normalized, a NaN, a negative value) is regenerated; a bad spec is refused with a one-line error.
TEST(Chermain2020Dictionary, CacheRoundTripAndRejection) {
    const ch::DictionarySpec spec = smallSpec();
    fs::path dir = test::makeTempDir("chermain2020_cache");
    ch::LoadedDictionary first = ch::loadOrGenerateDictionary(spec, dir, 2);
    EXPECT_FALSE(first.fromCache);
    EXPECT_TRUE(first.stored);
    ch::LoadedDictionary second = ch::loadOrGenerateDictionary(spec, dir, 2);
    EXPECT_TRUE(second.fromCache);
    EXPECT_EQ(first.dictionary.values, second.dictionary.values);

    fs::path file = dir / ch::dictionaryCacheFileName(spec);
    std::string bytes;
    {
        std::ifstream in(file, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    bytes[bytes.size() - 100] ^= 0x55;   // inside the payload: the checksum fails
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
    ch::LoadedDictionary third = ch::loadOrGenerateDictionary(spec, dir, 2);
    EXPECT_FALSE(third.fromCache);
    EXPECT_EQ(first.dictionary.values, third.dictionary.values);

    auto payload = [&](std::vector<float> v) {
        return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float));
    };
    std::vector<float> good = first.dictionary.values;
    EXPECT_TRUE(ch::validDictionaryValues(spec, payload(good)));
    std::vector<float> scaled = good;
    for (int j = 0; j < spec.resolution; ++j) scaled[size_t(j)] *= 1.01f;   // one marginal 1 % too heavy
    EXPECT_FALSE(ch::validDictionaryValues(spec, payload(scaled)));
    std::vector<float> nan = good;
    nan[5] = std::nanf("");
    EXPECT_FALSE(ch::validDictionaryValues(spec, payload(nan)));
    std::vector<float> negative = good;
    negative[7] = -negative[7];
    EXPECT_FALSE(ch::validDictionaryValues(spec, payload(negative)));
    EXPECT_FALSE(ch::validDictionaryValues(spec, payload(std::vector<float>(good.begin(), good.end() - 1))));
    // A right-checksum file of wrong values (written by a buggy or hostile program) is regenerated too.
    cache::CacheDir(dir).store(ch::dictionaryCacheFileName(spec), {"chermain2020-dictionary", 1, spec.text()},
                               payload(scaled));
    ch::LoadedDictionary fourth = ch::loadOrGenerateDictionary(spec, dir, 2);
    EXPECT_FALSE(fourth.fromCache);
    EXPECT_EQ(first.dictionary.values, fourth.dictionary.values);

    ch::DictionarySpec bad = spec;
    bad.marginals = 6;
    EXPECT_THROW(ch::generateDictionary(bad), UsageError);
    bad = spec;
    bad.lobeStd = 1.0;
    EXPECT_THROW(ch::loadOrGenerateDictionary(bad, dir), UsageError);
}

// Generation time of the authors' dictionary (16 x 192 x 64) on this machine, 2 threads; printed, not asserted.
TEST(Chermain2020Dictionary, GenerationTimeOfTheAuthorsSize) {
    if (!std::getenv("GLIMMER_MEASURE")) GTEST_SKIP() << "set GLIMMER_MEASURE=1 to time the generation";
    Stopwatch clock;
    ch::Dictionary d = ch::generateDictionary(ch::DictionarySpec{}, 2);
    std::printf("chermain2020 dictionary 16 x 192 x 64: generated in %.0f ms on 2 threads\n", clock.elapsedMs());
    EXPECT_EQ(d.values.size(), ch::DictionarySpec{}.valueCount());
}
