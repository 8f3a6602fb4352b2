#include "glints/chermain2020/dictionary.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <thread>

#include "core/cache_file.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/log.h"

namespace glimmer::chermain2020 {

namespace {

constexpr uint32_t kCacheVersion = 1;   // bump when the generator's output changes
constexpr double kPi = 3.14159265358979323846;

// SplitMix64 (Steele, Lea, Flood 2014): a small, well-mixed, portable stream; one stream per marginal so the
// marginals can be generated in any order on any number of threads with the same result.
struct SplitMix64 {
    uint64_t state;
    uint64_t next() {
        uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    // Uniform in (0, 1): 53 random bits, never 0.
    double uniform() { return (double(next() >> 11) + 0.5) * (1.0 / 9007199254740992.0); }
};

}  // namespace

double DictionarySpec::sigmaDict() const { return alphaDict / std::sqrt(2.0); }

std::string DictionarySpec::text() const {
    char text[200];
    std::snprintf(text, sizeof text, "levels=%d marginals=%d resolution=%d alpha_dict=%.9g lobe_std=%.9g seed=%llu "
                  "means=N(0,sd^2-sl^2) texel=centre", levels, marginals, resolution, alphaDict, lobeStd,
                  static_cast<unsigned long long>(seed));
    return text;
}

void DictionarySpec::validate() const {
    if (levels < 1 || levels > 20) throw UsageError("chermain2020 dictionary: levels must be 1..20");
    if (marginals < 4 || marginals > 1024 || marginals % 4 != 0)
        throw UsageError("chermain2020 dictionary: marginals must be a multiple of 4 in 4..1024");
    if (resolution < 4 || resolution > 1024) throw UsageError("chermain2020 dictionary: resolution must be 4..1024");
    if (!(alphaDict > 0.0 && alphaDict <= 4.0)) throw UsageError("chermain2020 dictionary: alpha_dict must be in (0, 4]");
    if (!(lobeStd > 0.0 && lobeStd < sigmaDict()))
        throw UsageError("chermain2020 dictionary: lobe_std must be in (0, alpha_dict / sqrt 2)");
}

double Dictionary::integral(int level, int m) const {
    const float* v = marginal(level, m);
    double sum = 0.0;
    for (int j = 0; j < spec.resolution; ++j) sum += v[j];
    return 2.0 * spec.texelWidth() * sum;
}

std::vector<double> lobeMeans(const DictionarySpec& spec, int m) {
    const size_t count = size_t(1) << (spec.levels - 1);
    // The lobes add their own variance: drawing the means with sigma_dict^2 - sigma_lobe^2 makes every level's
    // expected marginal exactly N(0, sigma_dict^2), the Beckmann marginal the method converges to.
    const double sigmaMeans = std::sqrt(spec.sigmaDict() * spec.sigmaDict() - spec.lobeStd * spec.lobeStd);
    SplitMix64 rng{spec.seed ^ (0xd1b54a32d192ed03ull * uint64_t(m + 1))};
    std::vector<double> means(count);
    for (size_t k = 0; k < count; k += 2) {   // Box-Muller: two normal variates per pair of uniforms
        double r = std::sqrt(-2.0 * std::log(rng.uniform())), phi = 2.0 * kPi * rng.uniform();
        means[k] = sigmaMeans * r * std::cos(phi);
        if (k + 1 < count) means[k + 1] = sigmaMeans * r * std::sin(phi);
    }
    return means;
}

Dictionary generateDictionary(const DictionarySpec& spec, int threads, const std::function<void(double)>& progress) {
    spec.validate();
    Dictionary dict;
    dict.spec = spec;
    dict.values.assign(spec.valueCount(), 0.0f);
    const int res = spec.resolution;
    const double h = spec.texelWidth(), sl = spec.lobeStd;
    // A lobe reaches at most 10 sigma_lobe: beyond, g < 2e-22 of its peak (far below float precision of the sums).
    const double reach = 10.0 * sl;
    const int workers = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    std::atomic<int> next{0}, done{0};
    std::mutex progressMutex;
    auto work = [&] {
        std::vector<double> acc(static_cast<size_t>(res), 0.0);
        for (int m = next++; m < spec.marginals; m = next++) {
            std::vector<double> means = lobeMeans(spec, m);
            std::fill(acc.begin(), acc.end(), 0.0);
            size_t added = 0;
            for (int level = 0; level < spec.levels; ++level) {
                // Level l holds the first 2^l means: add the new ones to the running sums of level l - 1.
                size_t count = size_t(1) << level;
                for (; added < count; ++added)
                    for (double centre : {means[added], -means[added]}) {
                        int j0 = std::max(0, int(std::ceil((centre - reach) / h - 0.5)));
                        int j1 = std::min(res - 1, int(std::floor((centre + reach) / h - 0.5)));
                        for (int j = j0; j <= j1; ++j) {
                            double d = (j + 0.5) * h - centre;
                            acc[size_t(j)] += std::exp(-0.5 * d * d / (sl * sl));
                        }
                    }
                // P_l(x_j) = acc_j / (2^(l+1) sqrt(2 pi) sigma_lobe), normalized so that 2 h sum_j P_l(x_j) = 1 (the truncation
                // at 4 sigma_dict and the sampling lose a little mass; the tests bound how much).
                double sum = 0.0;
                for (double a : acc) sum += a;
                float* out = dict.values.data() + (size_t(level) * spec.marginals + m) * res;
                if (sum <= 0.0) {   // every lobe beyond the table (only for absurd specs): a flat marginal
                    for (int j = 0; j < res; ++j) out[j] = float(1.0 / (2.0 * h * res));
                    continue;
                }
                double scale = 1.0 / (2.0 * h * sum);
                for (int j = 0; j < res; ++j) out[j] = float(acc[size_t(j)] * scale);
            }
            int finished = ++done;
            if (progress) {
                std::lock_guard<std::mutex> lock(progressMutex);
                progress(double(finished) / spec.marginals);
            }
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < workers; ++t) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    return dict;
}

bool validDictionaryValues(const DictionarySpec& spec, std::string_view bytes) {
    if (bytes.size() != spec.valueCount() * sizeof(float)) return false;
    const double h = spec.texelWidth();
    for (size_t start = 0; start < spec.valueCount(); start += size_t(spec.resolution)) {
        double sum = 0.0;
        for (int j = 0; j < spec.resolution; ++j) {
            float v;
            std::memcpy(&v, bytes.data() + (start + size_t(j)) * sizeof(float), sizeof v);
            if (!(v >= 0.0f) || !std::isfinite(v)) return false;   // also rejects NaN
            sum += v;
        }
        if (!(std::abs(2.0 * h * sum - 1.0) <= 1e-4)) return false;
    }
    return true;
}

std::string dictionaryCacheFileName(const DictionarySpec& spec) {
    return "chermain2020_dictionary_" + cache::contentHash(spec.text()) + ".bin";
}

LoadedDictionary loadOrGenerateDictionary(const DictionarySpec& spec, const std::filesystem::path& cacheDir,
                                          int threads) {
    spec.validate();
    LoadedDictionary loaded;
    loaded.dictionary.spec = spec;
    cache::CacheDir dir(cacheDir);
    const cache::CacheKey key{"chermain2020-dictionary", kCacheVersion, spec.text()};
    const std::string name = dictionaryCacheFileName(spec);
    if (std::optional<std::string> bytes = dir.load(name, key, spec.valueCount() * sizeof(float),
                                                    [&](std::string_view b) { return validDictionaryValues(spec, b); })) {
        loaded.dictionary.values.resize(spec.valueCount());
        std::memcpy(loaded.dictionary.values.data(), bytes->data(), bytes->size());
        loaded.fromCache = true;
        return loaded;
    }
    log::info("chermain2020: generating the dictionary (", spec.levels, " levels x ", spec.marginals,
              " marginals x ", spec.resolution, " texels) ...");
    Stopwatch clock;
    int lastQuarter = 0;
    loaded.dictionary = generateDictionary(spec, threads, [&](double fraction) {
        int quarter = int(fraction * 4.0);
        if (quarter > lastQuarter && quarter < 4) {
            lastQuarter = quarter;
            log::info("chermain2020: dictionary ", quarter * 25, " %");
        }
    });
    loaded.generationMs = clock.elapsedMs();
    const std::vector<float>& v = loaded.dictionary.values;
    loaded.stored = dir.store(name, key, std::string_view(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float)));
    log::info("chermain2020: dictionary generated in ", loaded.generationMs, " ms",
              loaded.stored ? ", cached in " + (cacheDir / name).string() : std::string(", not cached"));
    return loaded;
}

}  // namespace glimmer::chermain2020
