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

#include "bench/temporal.h"
#include "core/cache_file.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/files.h"
#include "core/image_io.h"
#include "glints/chermain2020/dictionary.h"
#include "glints/chermain2020/resources.h"
#include "checks/method_checks.h"
#include "reference/method_probe.h"
#include "reference/chermain2020_reference.h"
#include "platform/context.h"
#include "render/aov.h"
#include "offscreen/offscreen.h"
#include "scene/builtin_scenes.h"
#include "support/golden.h"
#include "support/measure.h"
#include "support/process.h"
#include "support/test_needs.h"

using namespace glimmer;

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h); the dictionary is CPU only.
GLIMMER_SUITE_NEEDS(Chermain2020Texture, GlContext);
GLIMMER_SUITE_NEEDS(Chermain2020Lobes, GlContext);
GLIMMER_SUITE_NEEDS(Chermain2020Reference, GlContext);
GLIMMER_SUITE_NEEDS(Chermain2020Convergence, GlContext);
GLIMMER_SUITE_NEEDS(Chermain2020Check, GlContext);
GLIMMER_SUITE_NEEDS(Chermain2020Golden, GlContext);
GLIMMER_SUITE_NEEDS(Chermain2021AntiAliasing, GlContext);
GLIMMER_SUITE_NEEDS(Chermain2021Lean, GlContext);
GLIMMER_SUITE_NEEDS(Chermain2020Cache, GlContext);

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

// The dictionary: level l of every marginal is the mixture of exactly 2^(l+1) Gaussian lobes (2^l means and their mirror
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

// The dictionary: the marginals encode the Beckmann marginal N(0, sigma_dict^2) of the dictionary's roughness. Each
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

// Generation time of the authors' dictionary (16 x 192 x 64) on this machine, 2 threads, and the time to read it
// back from a cache folder (load + checksum + value check); printed, not asserted.
TEST(Chermain2020Dictionary, GenerationTimeOfTheAuthorsSize) {
    if (!test::fullMeasurement()) GTEST_SKIP() << "set GLIMMER_MEASURE=1 to time the generation";
    fs::path dir = test::makeTempDir("chermain2020_timing");
    Stopwatch clock;
    ch::LoadedDictionary generated = ch::loadOrGenerateDictionary(ch::DictionarySpec{}, dir, 2);
    double generateMs = clock.elapsedMs();
    clock.restart();
    ch::LoadedDictionary loaded = ch::loadOrGenerateDictionary(ch::DictionarySpec{}, dir, 2);
    double loadMs = clock.elapsedMs();
    ASSERT_FALSE(generated.fromCache);
    ASSERT_TRUE(loaded.fromCache);
    std::printf("chermain2020 dictionary 16 x 192 x 64: generated in %.0f ms (of which %.0f ms generation) on 2 "
                "threads, read from the cache in %.1f ms\n", generateMs, generated.generationMs, loadMs);
}

namespace {

std::unique_ptr<GLContext> makeContext() { return createHeadlessContext(Backend::Egl); }

RenderResult renderWith(const std::string& scene, const std::string& method, const std::vector<std::string>& sets,
                        const std::string& aov = "final", int size = 256) {
    RenderRequest request;
    request.scene = scene;
    request.environment = "none";   // glints respond to the lights; the environment would add a smooth term only
    request.width = request.height = size;
    request.settings.method = method;
    for (const std::string& s : sets) request.settings.apply(s);
    request.settings.debugView = findAov(aov).viewId;
    return renderOffscreen(request);
}

// Local maxima of a row-major n x n grid (strictly above the 8 neighbours and above `floor`).
int countPeaks(const std::vector<float>& v, int n, float floor) {
    int peaks = 0;
    for (int y = 1; y + 1 < n; ++y)
        for (int x = 1; x + 1 < n; ++x) {
            float c = v[size_t(y) * n + x];
            if (c <= floor) continue;
            bool top = true;
            for (int dy = -1; dy <= 1 && top; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if ((dx || dy) && v[size_t(y + dy) * n + x + dx] >= c) { top = false; break; }
            peaks += top;
        }
    return peaks;
}

}  // namespace

// The shader's texture is the table (level 0 within half-float rounding, 1e-3 relative; every mip normalized like
// the table, 2 h_k sum = 1 within 2e-3) and the GLSL constants are the generator's spec.
TEST(Chermain2020Texture, TextureIsTheTableAndShaderConstantsTheSpec) {
    auto context = makeContext();
    const ch::Dictionary& d = defaultDictionary();
    const ch::DictionarySpec& spec = d.spec;
    gl::Texture texture = uploadChermainDictionary(d);
    const int layers = spec.levels * spec.marginals / 4;
    for (int mip = 0; (spec.resolution >> mip) >= 1; ++mip) {
        const int w = spec.resolution >> mip;
        std::vector<float> texels(size_t(w) * layers * 4);
        glGetTextureImage(texture.id(), mip, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(float)), texels.data());
        for (int level = 0; level < spec.levels; level += 5)
            for (int m = 0; m < spec.marginals; m += 7) {
                const float* row = texels.data() + size_t(level * spec.marginals / 4 + m / 4) * w * 4;
                double sum = 0.0;
                for (int j = 0; j < w; ++j) {
                    float v = row[size_t(j) * 4 + m % 4];
                    sum += v;
                    if (mip == 0) ASSERT_NEAR(v, d.at(level, m, j), 1e-3 * d.at(level, m, j) + 1e-6);
                }
                EXPECT_NEAR(2.0 * spec.range() / w * sum, 1.0, 2e-3) << "mip " << mip << " level " << level;
            }
    }
    std::ifstream in(defaultShaderDir() / "glints" / "chermain2020" / "chermain2020_dictionary.glsl");
    std::stringstream text;
    text << in.rdbuf();
    auto constant = [&](const std::string& name) {
        std::smatch match;
        std::string source = text.str();
        EXPECT_TRUE(std::regex_search(source, match, std::regex(name + "\\s*=\\s*([0-9.]+)"))) << name;
        return match.size() > 1 ? std::stod(match[1]) : -1.0;
    };
    EXPECT_EQ(constant("CHERMAIN_LEVELS"), spec.levels);
    EXPECT_EQ(constant("CHERMAIN_MARGINALS"), spec.marginals);
    EXPECT_EQ(constant("CHERMAIN_ROWS_PER_LEVEL"), spec.marginals / 4);
    EXPECT_EQ(constant("CHERMAIN_TEXELS"), spec.resolution);
    EXPECT_NEAR(constant("CHERMAIN_ALPHA_DICT"), spec.alphaDict, 1e-7);
    EXPECT_NEAR(constant("CHERMAIN_LOBE_STD"), spec.lobeStd, 1e-7);
    EXPECT_NEAR(constant("CHERMAIN_SIGMA_DICT"), spec.sigmaDict(), 1e-7);
    EXPECT_NEAR(constant("CHERMAIN_RANGE"), spec.range(), 1e-7);
}

// Resolved peaks of a tabulated marginal over the whole line (the table mirrored at 0, as the GPU reads it).
int marginalPeaks(const ch::Dictionary& d, int level, int m) {
    const int res = d.spec.resolution;
    std::vector<float> line(size_t(2 * res));
    for (int j = 0; j < res; ++j) line[size_t(res + j)] = line[size_t(res - 1 - j)] = d.at(level, m, j);
    float top = *std::max_element(line.begin(), line.end());
    int peaks = 0;
    for (int j = 1; j + 1 < 2 * res; ++j)
        peaks += line[size_t(j)] > line[size_t(j - 1)] && line[size_t(j)] >= line[size_t(j + 1)] &&
                 line[size_t(j)] > 1e-3f * top;
    return peaks;
}

// Alg. 3 lines 5-6: a cell of level l holds n = e^log_density 4^(l - (L - 1)) microfacets per unit UV area
// and uses the dictionary level log4 n (footprint AOV z, without density randomization); its NDF is the product
// of two marginals of that level, each a mixture of 2^(l_dist+1) lobes (LevelsAreMixtures... above): 4^(l_dist+1)
// lobes per cell, of which those closer than about two lobe deviations merge. Counted on the real shader:
// footprints of exactly one grid level (minor axis 2^-10 UV: level 5, no blend), 4 % of the cells non-empty so
// that most footprints see one cell, D scanned over a 256 x 256 grid of slopes (0.66 lobe deviations a step). For
// each footprint with exactly one non-empty cell (which cell, and which two marginals it drew, from the CPU
// reference) the count of local maxima is the product of the two marginals' resolved peaks (exactly in at least
// half of them, within max(2, 10 %) in all: a pair of lobes at the edge of being resolved may show as one or two
// maxima on the sampled grid; measured 22 of 24 exact) and the mean count is within 10 %. The lobes the dictionary
// resolves per marginal are printed against 2^(l_dist+1) (over the 192 marginals: 1.93 / 2, 3.59 / 4, 6.05 / 8).
TEST(Chermain2020Lobes, CellNdfIsTheProductOfTwoMarginalsOfLevelLog4N) {
    auto context = makeContext();
    const ch::Dictionary& d = defaultDictionary();
    const int n = 256, cellLevel = 5, levels = d.spec.levels;
    const double extent = 1.7;   // slopes in [-extent, extent]^2: the dictionary's 4 sigma for alpha 0.5, rotated
    for (int lDist = 0; lDist <= 2; ++lDist) {
        double resolved = 0.0;
        for (int m = 0; m < d.spec.marginals; ++m) resolved += marginalPeaks(d, lDist, m) / double(d.spec.marginals);
        std::printf("l_dist %d: %.2f resolved peaks per marginal of %d lobes\n", lDist, resolved, 2 << lDist);
        double log4n = lDist + 0.25;
        float logDensity = float((log4n - cellLevel) * std::log(4.0) + 30.0 * std::log(2.0));
        ch::ReferenceParams params;
        params.logDensity = logDensity;
        params.densityRandomization = 0.0f;
        params.relativeArea = 0.04f;
        GlintMethodProbe probe("chermain2020", {{"log_density", logDensity},
                                                {"density_randomization", 0.0f},
                                                {"microfacet_relative_area", 0.04f}});
        int single = 0, matching = 0;
        double measuredSum = 0.0, expectedSum = 0.0;
        for (int f = 0; f < 400 && single < 8; ++f) {
            glm::vec2 uv(0.37f + 0.0131f * f, 0.61f + 0.0297f * f), dx(std::exp2(-10.0f), 0.0f), dy(0.0f, std::exp2(-10.0f));
            std::vector<ch::WeightedCell> cells = ch::footprintCells(params, uv, dx, dy, levels);
            int nonEmpty = 0;
            const ch::WeightedCell* lit = nullptr;
            for (const ch::WeightedCell& c : cells)
                if (!c.draw.empty) ++nonEmpty, lit = &c;
            if (nonEmpty != 1) continue;
            ++single;
            ASSERT_EQ(lit->draw.dictionaryLevel, lDist);
            std::vector<GlintProbeInput> inputs(size_t(n) * n);
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    GlintProbeInput& in = inputs[size_t(y) * n + x];
                    glm::vec2 m(extent * (2.0 * (x + 0.5) / n - 1.0), extent * (2.0 * (y + 0.5) / n - 1.0));
                    in.uv = uv;
                    in.duvdx = dx;
                    in.duvdy = dy;
                    in.h = glm::normalize(glm::vec3(-m, 1.0f));
                    in.alpha = 0.5f;
                    in.ndf = 1;   // Beckmann: the dictionary's own distribution, unwarped
                }
            std::vector<GlintProbeOutput> out = probe.run(inputs);
            ASSERT_NEAR(out[0].footprint.y, float(cellLevel), 1e-4);   // LOD
            ASSERT_NEAR(out[0].footprint.z, float(log4n), 1e-3);       // log4 n of the cells
            std::vector<float> p22(out.size());
            float peak = 0.0f;
            for (size_t i = 0; i < out.size(); ++i) {
                float hz = inputs[i].h.z;
                p22[i] = out[i].D * hz * hz * hz * hz;
                peak = std::max(peak, p22[i]);
            }
            int measured = countPeaks(p22, n, 1e-3f * peak);
            int expected = marginalPeaks(d, lDist, lit->draw.marginalX) * marginalPeaks(d, lDist, lit->draw.marginalY);
            std::printf("  footprint %d: %d local maxima, marginals %d x %d resolve %d\n", f, measured,
                        lit->draw.marginalX, lit->draw.marginalY, expected);
            matching += measured == expected;
            // A pair of lobes at the edge of being resolved may show as one or two maxima on the sampled grid.
            EXPECT_LE(std::abs(measured - expected), std::max(2, expected / 10)) << "footprint " << f;
            measuredSum += measured;
            expectedSum += expected;
        }
        ASSERT_GE(single, 8) << "l_dist " << lDist;
        EXPECT_GE(matching, single / 2) << "l_dist " << lDist;
        EXPECT_NEAR(measuredSum / expectedSum, 1.0, 0.1) << "l_dist " << lDist;
    }
}

// The shader against the CPU reference (engine/reference/chermain2020_reference.h) on 3000 random pixels per
// parameter set: footprints from 1e-5 to 1e-1 UV with anisotropy up to 30, half vectors up to 70 degrees, GGX and
// Beckmann, alpha 0.05 .. 1, and parameter sets that switch each part on (defaults; no randomization; 30 % of the
// cells; anisotropic and correlated roughness; stretched glints; a LOD bias; another seed). Agreement within 2 %
// relative (plus 1e-4 of the smooth D) on at least 98 % of the pixels: the texture is half floats read by the
// hardware's 8-bit filter weights, and a few float roundings land on the other side of a cell or level boundary.
TEST(Chermain2020Reference, ShaderMatchesCpuReference) {
    auto context = makeContext();
    const ch::Dictionary& d = defaultDictionary();
    struct Case {
        std::string name;
        ParamValues values;
        ch::ReferenceParams params;
    };
    std::vector<Case> cases(7);
    cases[0].name = "defaults";
    cases[1].name = "zeta 0";
    cases[1].values = {{"density_randomization", 0.0f}};
    cases[1].params.densityRandomization = 0.0f;
    cases[2].name = "relative area 0.3";
    cases[2].values = {{"microfacet_relative_area", 0.3f}};
    cases[2].params.relativeArea = 0.3f;
    cases[3].name = "anisotropic correlated roughness";
    cases[3].values = {{"roughness_anisotropy", 2.5f}, {"slope_correlation", 0.5f}};
    cases[3].params.roughnessAnisotropy = 2.5f;
    cases[3].params.slopeCorrelation = 0.5f;
    cases[4].name = "stretched glints";
    cases[4].values = {{"glint_anisotropy", 4.0f}, {"max_anisotropy", 16.0f}};
    cases[4].params.glintAnisotropy = 4.0f;
    cases[4].params.maxAnisotropy = 16.0f;
    cases[5].name = "lod bias -1.5, log density 20";
    cases[5].values = {{"lod_bias", -1.5f}, {"log_density", 20.0f}};
    cases[5].params.lodBias = -1.5f;
    cases[5].params.logDensity = 20.0f;
    cases[6].name = "seed 7";
    cases[6].values = {{"seed", 7.0f}};
    cases[6].params.seed = 7.0f;
    for (const Case& c : cases) {
        GlintMethodProbe probe("chermain2020", c.values);
        std::mt19937 rng(29);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::vector<GlintProbeInput> inputs(3000);
        for (GlintProbeInput& in : inputs) {
            float size = std::exp2(-16.6f + 13.3f * unit(rng)), ratio = std::exp2(4.9f * unit(rng)), phi = 6.283f * unit(rng);
            glm::vec2 a(std::cos(phi), std::sin(phi)), b(-a.y, a.x);
            in.uv = glm::vec2(unit(rng), unit(rng)) * 8.0f - 4.0f;
            in.duvdx = a * size * ratio;
            in.duvdy = b * size;
            float theta = 1.22f * std::sqrt(unit(rng)), az = 6.283f * unit(rng);
            in.h = glm::vec3(std::sin(theta) * std::cos(az), std::sin(theta) * std::sin(az), std::cos(theta));
            in.alpha = 0.05f + 0.95f * unit(rng);
            in.ndf = int(unit(rng) * 2.0f);
        }
        std::vector<GlintProbeOutput> out = probe.run(inputs);
        size_t agree = 0, nonZero = 0;
        double worst = 0.0;
        for (size_t i = 0; i < inputs.size(); ++i) {
            const GlintProbeInput& in = inputs[i];
            double ref = ch::referenceD(d, c.params, in.uv, in.duvdx, in.duvdy, in.h, in.alpha, in.ndf);
            double err = std::abs(out[i].D - ref) / (std::abs(ref) + 1e-4 * out[i].smoothD + 1e-12);
            ASSERT_TRUE(std::isfinite(out[i].D) && out[i].D >= 0.0f) << c.name << " probe " << i;
            agree += err <= 0.02;
            nonZero += ref > 0.0;
            worst = std::max(worst, err);
        }
        std::printf("%-34s %zu / %zu within 2 %% (%zu non-zero), worst %.3g\n", c.name.c_str(), agree, inputs.size(),
                    nonZero, worst);
        EXPECT_GE(double(agree), 0.98 * double(inputs.size())) << c.name;
        EXPECT_GT(nonZero, inputs.size() / 3) << c.name;
    }
}

// Eq. 14 and the paper's claim: with many microfacets per cell the glinty BRDF converges to Cook-Torrance.
// Very high density (log_density 60: every cell beyond the dictionary, l_dist = L) renders exactly the smooth image
// (mean within 0.5 %, every 5x5-filtered pixel within 1 %). Dictionary levels alone (no density randomization; the
// density set so that the cells of the view's coarser level sit at log4 n = 15.4, below the smooth level, and
// log4 n reaches 9.4-14.4 at the finer ones) converge too: the mean within 2 %, the 5x5-filtered pixels within 10 %
// on 99 % of the pixels, and the per-pixel gap shrinks as the density grows (4 levels sparser: larger). Beckmann
// (the papers' base NDF) first, then GGX (our warp of the dictionary's Gaussian cells).
class Chermain2020Convergence : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(Chermain2020Convergence, HighDensityEqualsSmooth) {
    auto [scene, ndf] = GetParam();
    const int size = 96;
    std::vector<std::string> common = {"material.ndf=" + ndf};
    RenderResult smooth = renderWith(scene, "smooth", common, "final", size);
    std::vector<std::string> very = common;
    very.push_back("chermain2020.log_density=60");
    RenderResult veryHigh = renderWith(scene, "chermain2020", very, "final", size);
    ASSERT_EQ(veryHigh.stats["counts"]["non_finite_values"].get<size_t>(), 0u);
    checks::SmoothGap exact = checks::gapToSmooth(veryHigh.hdr, smooth.hdr, size, size, 2, 0.01);
    EXPECT_NEAR(exact.meanRatio, 1.0, 0.005) << scene << " " << ndf;
    EXPECT_EQ(exact.fractionAbove, 0.0) << scene << " " << ndf << ": worst " << exact.worstPixelError;

    // The density that puts the coarser level's cells at log4 n = 15.4: from the footprint AOV at log density 27
    // (z = log4 n of the finer level's cells; the coarser level holds 4 times more).
    RenderResult footprint = renderWith(scene, "chermain2020", {"chermain2020.log_density=27"}, "footprint", size);
    float maxLog4n = -1e30f;
    for (size_t i = 0; i < footprint.hdr.size(); i += 4)
        if (footprint.hdr[i + 1] > 0.0f) maxLog4n = std::max(maxLog4n, footprint.hdr[i + 2]);
    double logDensity = 27.0 + (15.4 - (maxLog4n + 1.0)) * std::log(4.0);
    double previousWorst = 1e30;
    for (double offset : {-4.0 * std::log(4.0), 0.0}) {
        std::vector<std::string> sets = common;
        sets.push_back("chermain2020.density_randomization=0");
        sets.push_back("chermain2020.log_density=" + std::to_string(logDensity + offset));
        RenderResult glinty = renderWith(scene, "chermain2020", sets, "final", size);
        checks::SmoothGap gap = checks::gapToSmooth(glinty.hdr, smooth.hdr, size, size, 2, 0.10);
        std::printf("%s %s log density %.2f: mean ratio %.4f, worst 5x5 pixel %.3f, %.2f %% beyond 10 %%\n",
                    scene.c_str(), ndf.c_str(), logDensity + offset, gap.meanRatio, gap.worstPixelError,
                    100.0 * gap.fractionAbove);
        EXPECT_NEAR(gap.meanRatio, 1.0, 0.02) << scene << " " << ndf << " offset " << offset;
        EXPECT_LT(gap.worstPixelError, previousWorst) << scene << " " << ndf;
        if (offset == 0.0) EXPECT_LE(gap.fractionAbove, 0.01) << scene << " " << ndf;
        previousWorst = gap.worstPixelError;
    }
}

INSTANTIATE_TEST_SUITE_P(ScenesAndNdfs, Chermain2020Convergence,
                         ::testing::Combine(::testing::Values("plane90", "plane25"),
                                            ::testing::Values("beckmann", "ggx")));

// The check-method rules every method is held to (glints/method_checks.h): the white furnace and finite values
// (the convergence rule's measure at the entry's `convergence` values is Chermain2020Convergence's first half; the
// constant-time rule fails by design: the EWA visits more cells for elongated footprints, up to max_anisotropy,
// docs/chermain2020.md has the numbers).
TEST(Chermain2020Check, FurnaceAndFiniteRulesPass) {
    for (const char* method : {"chermain2020", "chermain2021"}) {
        checks::CheckOptions options;
        // chermain2021 differs in the probes only by max_anisotropy (the probes give no surface derivatives and no
        // normal map): its furnace is chermain2020's.
        options.rules = std::string(method) == "chermain2020" ? std::vector<std::string>{"furnace", "finite"}
                                                              : std::vector<std::string>{"finite"};
        checks::CheckReport report = checks::checkMethod(method, options);
        std::string table = checks::formatTable(report);
        std::printf("%s\n", table.c_str());
        ASSERT_EQ(report.results.size(), options.rules.size()) << method;
        EXPECT_TRUE(report.passed()) << table;
    }
}

// Golden images (256 x 256; references in tests/golden/ref/, rewritten with GLIMMER_UPDATE_GOLDEN=1): the method's
// defaults on plane90 and the sphere, and chermain2021 (GGAA, LEAN) on the sphere.
class Chermain2020Golden : public ::testing::TestWithParam<std::pair<std::string, std::string>> {};

TEST_P(Chermain2020Golden, MatchesReference) {
    auto [method, scene] = GetParam();
    RenderResult result = renderWith(scene, method, {});
    EXPECT_EQ(result.stats["counts"]["non_finite_values"].get<size_t>(), 0u);
    test::GoldenComparison comparison =
        test::compareWithGolden(method + "_" + scene, result.display, result.width, result.height);
    EXPECT_TRUE(comparison.passed) << comparison.message;
}

INSTANTIATE_TEST_SUITE_P(Views, Chermain2020Golden,
                         ::testing::Values(std::make_pair(std::string("chermain2020"), std::string("plane90")),
                                           std::make_pair(std::string("chermain2020"), std::string("sphere")),
                                           std::make_pair(std::string("chermain2021"), std::string("sphere"))),
                         [](const auto& info) { return info.param.first + "_" + info.param.second; });

// Chermain et al. 2021: geometric glint anti-aliasing filters each glint over the pixel's range of half
// vectors, so glints stop popping as the half vector sweeps past them. Measured with `bench --temporal --motion
// light` (a still camera, the light turned 0.008 rad a frame; popping = mean |D_t - (D_t-1 + D_t+1) / 2| / mean D,
// which a smoothly moving highlight keeps near 0) on the sphere at 64 x 64 with alpha 0.1 and sparse glints (log
// density 12), where one pixel spans about 8 lobe widths of slope: chermain2021 (GGAA, the authors' kernel 0.5)
// pops at most 0.8 x as much as chermain2020 (measured 0.0060 against 0.0090) and flickers less; smooth pops
// under a fifth of chermain2020 (so the measure sees glints, not the highlight). Where a pixel spans less than one
// texel of the dictionary the hardware filter, hence GGAA, does nothing (docs/chermain2020.md).
TEST(Chermain2021AntiAliasing, GlintsPopLessUnderALightTurn) {
    bench::TemporalOptions options;
    options.scenes = {"sphere"};
    options.methods = {"smooth", "chermain2020", "chermain2021"};
    options.width = options.height = 64;
    options.frames = 5;
    options.step = 0.008;
    options.motion = "light";
    options.environment = "none";
    options.extraSets = {"material.alpha=0.1", "chermain2020.log_density=12", "chermain2021.log_density=12"};
    std::vector<bench::TemporalResult> results = bench::runTemporal(options);
    ASSERT_EQ(results.size(), 3u);
    const bench::TemporalResult &smooth = results[0], &without = results[1], &with = results[2];
    std::printf("popping: smooth %.4f, chermain2020 %.4f, chermain2021 %.4f; flicker %.4f, %.4f, %.4f\n",
                smooth.popping, without.popping, with.popping, smooth.meanFlicker, without.meanFlicker,
                with.meanFlicker);
    EXPECT_LT(smooth.popping, 0.2 * without.popping);
    EXPECT_LE(with.popping, 0.8 * without.popping);
    EXPECT_LT(with.meanFlicker, without.meanFlicker);
}

namespace {

// A sphere whose material has a normal map of random smooth bumps: 24 plane waves of random direction and phase
// with periods of 8 to 16 texels (whole waves per 64-texel tile), scaled to a slope deviation of 0.2: a Gaussian
// field of slopes, smooth at the texel scale, so that bilinear magnification does not change its statistics.
// Tiled 1.4 times per metre of UV: about 2 pixels per texel in a 1024-pixel view, 16 texels per pixel at 32.
std::string bumpySphereScene(const std::string& dir) {
    const int n = 64, waves = 24;
    std::mt19937 rng(3);
    std::vector<glm::dvec2> slope(size_t(n) * n, glm::dvec2(0.0));
    std::uniform_int_distribution<int> frequency(-8, 8);
    std::uniform_real_distribution<double> phase(0.0, 2.0 * M_PI);
    for (int w = 0; w < waves; ++w) {
        int kx, ky;
        do {
            kx = frequency(rng);
            ky = frequency(rng);
        } while (kx * kx + ky * ky < 16 || kx * kx + ky * ky > 64);   // period n / |k| in [8, 16] texels
        double ph = phase(rng);
        glm::dvec2 k(2.0 * M_PI * kx / n, 2.0 * M_PI * ky / n);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) slope[size_t(y) * n + x] += k * std::cos(k.x * (x + 0.5) + k.y * (y + 0.5) + ph);
    }
    double variance = 0.0;
    for (const glm::dvec2& s : slope) variance += 0.5 * glm::dot(s, s) / slope.size();
    std::vector<uint8_t> rgba(size_t(n) * n * 4);
    for (size_t i = 0; i < slope.size(); ++i) {
        glm::dvec2 m = slope[i] * (0.2 / std::sqrt(variance));
        glm::dvec3 normal = glm::normalize(glm::dvec3(-m, 1.0));
        for (int c = 0; c < 3; ++c) rgba[4 * i + c] = uint8_t(std::lround((normal[c] * 0.5 + 0.5) * 255.0));
        rgba[4 * i + 3] = 255;
    }
    std::string png = dir + "/bumps.png";
    writePng(png, rgba.data(), n, n);
    std::string path = dir + "/bumpy_sphere.json";
    std::ofstream(path) << "{\"base\": \"sphere\", \"materials\": [{\"name\": \"sphere\", \"normalTexture\": \"" << png
                        << "\", \"uvScale\": 1.4}]}\n";
    return path;
}

}  // namespace

// Chermain et al. 2021: LEAN mapping moves the normal map's detail that a pixel cannot resolve into the
// NDF. A 32-pixel view of a bumpy sphere (16 normal-map texels per pixel) against the same view rendered at 1024
// pixels without LEAN (2 pixels per texel) and box-filtered 32 x 32: with LEAN the glint AOV's relative L2 error
// over the sphere is at most 0.7 x the error without it (which sees only the filtered, flattened normals: a
// highlight too sharp; measured 0.27 against 0.48), and its mean is within 5 % (measured 1.7 %). Smooth
// cells (log density 60) isolate the normal-map filtering from the glints. LEAN's second moments are those of the
// texels, which equal the magnified surface's only for normal maps smooth at the texel scale: on per-texel noise a
// supersampled view sees the bilinearly interpolated normals, whose variance is lower (docs/chermain2020.md).
TEST(Chermain2021Lean, NormalMapFilteringMatchesTheResolvedNormalMap) {
    std::string scene = bumpySphereScene(test::makeTempDir("chermain2021_lean"));
    std::vector<std::string> common = {"chermain2021.anti_aliasing=none", "chermain2021.log_density=60"};
    auto glint = [&](int size, const std::string& filtering) {
        std::vector<std::string> sets = common;
        sets.push_back("chermain2021.normal_filtering=" + filtering);
        RenderResult r = renderWith(scene, "chermain2021", sets, "glint", size);
        EXPECT_EQ(r.stats["counts"]["non_finite_values"].get<size_t>(), 0u);
        std::vector<double> d(size_t(size) * size);
        for (size_t i = 0; i < d.size(); ++i) d[i] = r.hdr[4 * i];
        return d;
    };
    const int n = 32, factor = 32;
    std::vector<double> big = glint(n * factor, "none"), reference(size_t(n) * n, 0.0);
    for (int y = 0; y < n * factor; ++y)
        for (int x = 0; x < n * factor; ++x)
            reference[size_t(y / factor) * n + x / factor] += big[size_t(y) * n * factor + x] / (factor * factor);
    auto error = [&](const std::vector<double>& d, double& meanRatio) {
        double e2 = 0, r2 = 0, sd = 0, sr = 0;
        for (size_t i = 0; i < d.size(); ++i) {
            if (reference[i] <= 0.0) continue;
            e2 += (d[i] - reference[i]) * (d[i] - reference[i]);
            r2 += reference[i] * reference[i];
            sd += d[i];
            sr += reference[i];
        }
        meanRatio = sd / sr;
        return std::sqrt(e2 / r2);
    };
    double meanNone, meanLean;
    double none = error(glint(n, "none"), meanNone), lean = error(glint(n, "lean"), meanLean);
    std::printf("relative L2 error against the resolved normal map: without LEAN %.3f (mean %.3f), LEAN %.3f "
                "(mean %.3f)\n", none, meanNone, lean, meanLean);
    EXPECT_LE(lean, 0.7 * none);
    EXPECT_NEAR(meanLean, 1.0, 0.05);
}

// With several lights the cells' draws are made once per pixel and kept (glintSetup), with one light where glintD
// evaluates them: the first light's D (glint AOV) is the same either way, on plane90 (every pixel cached) and
// plane25 (elongated footprints overflow the cache and draw per light), 1e-5 relative.
TEST(Chermain2020Cache, SharedDrawsGiveTheSameNdf) {
    for (const char* scene : {"plane90", "plane25"}) {
        RenderResult one = renderWith(scene, "chermain2020", {"light.count=1"}, "glint", 64);
        RenderResult three = renderWith(scene, "chermain2020", {"light.count=3"}, "glint", 64);
        size_t lit = 0;
        for (size_t i = 0; i < one.hdr.size(); i += 4) {
            ASSERT_NEAR(three.hdr[i], one.hdr[i], 1e-5f * std::max(one.hdr[i], 1.0f)) << scene << " pixel " << i / 4;
            lit += one.hdr[i] > 0.0f;
        }
        EXPECT_GT(lit, one.hdr.size() / 8) << scene;
    }
}
