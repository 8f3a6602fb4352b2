#include "glints/wang2020/wang2020_dpf.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <thread>

#include "core/cache_file.h"
#include "core/clock.h"
#include "core/error.h"
#include "core/log.h"

namespace glimmer::wang2020 {

namespace {

constexpr uint32_t kCacheVersion = 2;  // 2: core/cache_file.h container

int threadCount(int requested) {
    if (requested > 0) return requested;
    return std::max(1u, std::thread::hardware_concurrency());
}

// Runs body(row) for rows [0, rows) on `threads` threads (rows interleaved so the load is balanced).
template <class Body>
void parallelRows(int rows, int threads, Body body) {
    std::vector<std::thread> pool;
    std::atomic<int> next{0};
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (int r = next++; r < rows; r = next++) body(r);
        });
    for (std::thread& th : pool) th.join();
}

// Orthonormal frame around unit vector z.
void frameAround(glm::vec3 z, glm::vec3& x, glm::vec3& y) {
    glm::vec3 a = std::abs(z.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    x = glm::normalize(glm::cross(a, z));
    y = glm::cross(z, x);
}

// Quadrature points of the cone of half-angle gamma around axis: rings of equal angular width, 6(r+1) azimuths on
// ring r, each point weighted by its sector's solid angle (the weights sum to the cone's solid angle).
template <class Visit>
void forEachConePoint(glm::vec3 axis, float gamma, int rings, Visit visit) {
    glm::vec3 x, y;
    frameAround(axis, x, y);
    for (int r = 0; r < rings; ++r) {
        float lo = gamma * r / rings, hi = gamma * (r + 1) / rings, mid = 0.5f * (lo + hi);
        int azimuths = 6 * (r + 1);
        float weight = 2.0f * kPi * (std::cos(lo) - std::cos(hi)) / azimuths;
        for (int a = 0; a < azimuths; ++a) {
            float phi = 2.0f * kPi * (a + 0.5f * (r % 2)) / azimuths;
            visit(std::cos(mid) * axis + std::sin(mid) * (std::cos(phi) * x + std::sin(phi) * y), weight);
        }
    }
}

template <class F>
float coneIntegral(glm::vec3 axis, float gamma, int rings, F f) {
    double sum = 0.0;
    forEachConePoint(axis, gamma, rings, [&](glm::vec3 d, float weight) { sum += double(weight) * f(d); });
    return float(sum);
}

// Cache I/O through core/cache_file.h: the header carries the resolution, alpha and base gamma, a checksum
// covers the payload, and the values are checked (a DPF table holds finite values in [0, 1], Sec. 4.4 and the
// clamp in generateDpf) before they are trusted.
std::string cacheFileName(float alpha, DpfResolution res, ParticleNdf ndf) {
    char name[96];
    std::snprintf(name, sizeof name, "wang2020_dpf_%sa%.3f_%dx%dx%d.bin", ndf == ParticleNdf::Ggx ? "ggx_" : "", alpha,
                  res.thetaI, res.thetaO, res.phi);
    return name;
}

cache::CacheKey cacheKey(float alpha, DpfResolution res, ParticleNdf ndf) {
    char parameters[160];
    std::snprintf(parameters, sizeof parameters, "alpha=%.6f thetaI=%d thetaO=%d phi=%d gamma=%.6f rings=4%s", alpha,
                  res.thetaI, res.thetaO, res.phi, kBaseGamma, ndf == ParticleNdf::Ggx ? " ndf=ggx" : "");
    return {"wang2020-dpf", kCacheVersion, parameters};
}

// A table of zeros passes the range check but has no glints at all: never a real DPF, so it is rejected too.
bool validDpfValues(std::string_view bytes) {
    bool anyPositive = false;
    for (size_t at = 0; at + sizeof(float) <= bytes.size(); at += sizeof(float)) {
        float v;
        std::memcpy(&v, bytes.data() + at, sizeof v);
        if (!(v >= 0.0f && v <= 1.0f)) return false;  // also rejects NaN
        anyPositive |= v > 0.0f;
    }
    return anyPositive;
}

bool readTable(const cache::CacheDir& dir, float alpha, ParticleNdf ndf, DpfTable& table) {
    std::optional<std::string> bytes = dir.load(cacheFileName(alpha, table.res, ndf), cacheKey(alpha, table.res, ndf),
                                                table.res.size() * sizeof(float), validDpfValues);
    if (!bytes) return false;
    table.values.resize(table.res.size());
    std::memcpy(table.values.data(), bytes->data(), bytes->size());
    return true;
}

bool writeTable(const cache::CacheDir& dir, float alpha, ParticleNdf ndf, const DpfTable& table) {
    return dir.store(cacheFileName(alpha, table.res, ndf), cacheKey(alpha, table.res, ndf),
                     std::string_view(reinterpret_cast<const char*>(table.values.data()), table.values.size() * sizeof(float)));
}

}  // namespace

glm::vec3 sphericalDirection(float theta, float phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

float beckmannD(glm::vec3 m, float alpha) {
    if (m.z <= 0.0f) return 0.0f;
    float c2 = m.z * m.z, t2 = (1.0f - c2) / c2, a2 = alpha * alpha;
    return std::exp(-t2 / a2) / (kPi * a2 * c2 * c2);
}

const char* particleNdfName(ParticleNdf ndf) { return ndf == ParticleNdf::Ggx ? "GGX" : "Beckmann"; }

float ggxD(glm::vec3 m, float alpha) {
    if (m.z <= 0.0f) return 0.0f;
    float c2 = m.z * m.z, a2 = alpha * alpha, t = c2 * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * t * t);
}

float reflectionDensity(glm::vec3 wi, glm::vec3 wo, float alpha, ParticleNdf ndf) {
    glm::vec3 h = wi + wo;
    float len = glm::length(h);
    if (len < 1e-6f) return 0.0f;
    h /= len;
    float ih = std::abs(glm::dot(wi, h));
    if (ih < 1e-6f) return 0.0f;
    return (ndf == ParticleNdf::Ggx ? ggxD(h, alpha) : beckmannD(h, alpha)) * h.z / (4.0f * ih);
}

float dpfByQuadrature(glm::vec3 wi, glm::vec3 wo, float alpha, float gamma, int rings, ParticleNdf ndf) {
    return coneIntegral(wo, gamma, rings, [&](glm::vec3 o) { return reflectionDensity(wi, o, alpha, ndf); });
}

float DpfTable::lookup(float thetaI, float thetaO, float phi) const {
    auto axis = [](float v, float range, int n, int& i0, float& f) {
        float x = std::clamp(v / range * n - 0.5f, 0.0f, float(n - 1));
        i0 = std::min(int(x), n - 2 < 0 ? 0 : n - 2);
        f = std::min(x - i0, 1.0f);
    };
    phi = std::abs(phi);
    if (phi > kPi) phi = 2.0f * kPi - phi;
    int a, b, c;
    float fa, fb, fc;
    axis(thetaI, 0.5f * kPi, res.thetaI, a, fa);
    axis(thetaO, 0.5f * kPi, res.thetaO, b, fb);
    axis(phi, kPi, res.phi, c, fc);
    float v = 0.0f;
    for (int k = 0; k < 8; ++k) {
        int da = k & 1, db = (k >> 1) & 1, dc = (k >> 2) & 1;
        float w = (da ? fa : 1 - fa) * (db ? fb : 1 - fb) * (dc ? fc : 1 - fc);
        if (w > 0.0f) v += w * at(a + da, b + db, c + dc);
    }
    return v;
}

float DpfTable::lookup(glm::vec3 wi, glm::vec3 wo) const {
    float ti = std::acos(std::clamp(wi.z, -1.0f, 1.0f)), to = std::acos(std::clamp(wo.z, -1.0f, 1.0f));
    float phi = std::atan2(wo.y, wo.x) - std::atan2(wi.y, wi.x);
    if (phi < 0.0f) phi += 2.0f * kPi;
    return lookup(ti, to, phi);
}

DpfTable generateDpf(float alpha, DpfResolution res, int threads, ParticleNdf ndf) {
    DpfTable table;
    table.res = res;
    table.gamma = kBaseGamma;
    table.values.assign(res.size(), 0.0f);
    parallelRows(res.thetaI, threadCount(threads), [&](int ti) {
        glm::vec3 wi = sphericalDirection((ti + 0.5f) * 0.5f * kPi / res.thetaI, 0.0f);
        for (int to = 0; to < res.thetaO; ++to)
            for (int p = 0; p < res.phi; ++p) {
                glm::vec3 wo = sphericalDirection((to + 0.5f) * 0.5f * kPi / res.thetaO, (p + 0.5f) * kPi / res.phi);
                table.values[(size_t(ti) * res.thetaO + to) * res.phi + p] =
                    std::min(dpfByQuadrature(wi, wo, alpha, kBaseGamma, 4, ndf), 1.0f);
            }
    });
    return table;
}

std::filesystem::path defaultDpfCacheDir() {
    if (const char* d = std::getenv("GLIMMER_DPF_CACHE"); d && *d) return d;
    if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return std::filesystem::path(d) / "glimmer";
    if (const char* d = std::getenv("HOME"); d && *d) return std::filesystem::path(d) / ".cache" / "glimmer";
    return std::filesystem::temp_directory_path() / "glimmer";
}

DpfSet loadOrGenerateDpfSet(DpfResolution res, const std::filesystem::path& cacheDir, int threads, ParticleNdf ndf) {
    DpfSet set;
    set.fromCache = true;
    Stopwatch clock;
    cache::CacheDir dir(cacheDir);
    bool stored = true;
    for (size_t k = 0; k < kRoughnessSamples.size(); ++k) {
        float alpha = kRoughnessSamples[k];
        DpfTable table;
        table.res = res;
        if (!readTable(dir, alpha, ndf, table)) {
            set.fromCache = false;
            Stopwatch one;
            table = generateDpf(alpha, res, threads, ndf);
            log::info("wang2020: DPF generation ", k + 1, "/", kRoughnessSamples.size(), " (", particleNdfName(ndf),
                      " alpha ", alpha, ", ",
                      res.thetaI, "x", res.thetaO, "x", res.phi, ") in ", one.elapsedMs(), " ms");
            stored = writeTable(dir, alpha, ndf, table) && stored;
        }
        set.tables.push_back(std::move(table));
    }
    if (!set.fromCache) {
        set.generationMs = clock.elapsedMs();
        log::info("wang2020: DPF tables generated in ", set.generationMs, " ms with ", threadCount(threads),
                  " threads", stored ? ", cached in " + cacheDir.string() : std::string(", not cached"));
    }
    return set;
}

DpfTable extractDpf(const DpfSet& set, float alpha) {
    const auto& s = kRoughnessSamples;
    if (!(alpha >= s.front() && alpha <= s.back()))
        throw UsageError("wang2020: roughness " + std::to_string(alpha) + " outside the DPF samples [0.02, 1]");
    size_t hi = 1;
    while (hi + 1 < s.size() && s[hi] < alpha) ++hi;
    float t = (alpha - s[hi - 1]) / (s[hi] - s[hi - 1]);
    DpfTable out = set.tables[hi - 1];
    const std::vector<float>& b = set.tables[hi].values;
    for (size_t i = 0; i < out.values.size(); ++i) out.values[i] = (1.0f - t) * out.values[i] + t * b[i];
    return out;
}

DpfTable accumulateDpf(const DpfTable& base, float gamma, int threads) {
    DpfTable out;
    out.res = base.res;
    out.gamma = gamma;
    out.values.assign(base.res.size(), 0.0f);
    const float invBase = 1.0f / coneSolidAngle(base.gamma);
    // One ring per degree of gamma (the table's own resolution): finer would only resample interpolated values.
    const int rings = std::max(2, int(std::ceil(gamma / kDegree)));
    const DpfResolution res = base.res;
    const size_t slice = size_t(res.thetaO) * res.phi;  // one theta_i row of the table
    // The cone's points around o and their bilinear taps in the (theta_o, phi) slice do not depend on theta_i
    // (wi sits at phi = 0 and at a cell centre of theta_i): compute the taps once per output (theta_o, phi) and
    // apply them to every theta_i row.
    parallelRows(res.thetaO, threadCount(threads), [&](int to) {
        std::vector<std::pair<uint32_t, float>> taps;
        for (int p = 0; p < res.phi; ++p) {
            taps.clear();
            glm::vec3 wo = sphericalDirection((to + 0.5f) * 0.5f * kPi / res.thetaO, (p + 0.5f) * kPi / res.phi);
            forEachConePoint(wo, gamma, rings, [&](glm::vec3 o, float weight) {
                if (o.z <= 0.0f) return;  // beyond the table: no reflection recorded there
                float thetaO = std::acos(std::clamp(o.z, -1.0f, 1.0f));
                float phi = std::abs(std::atan2(o.y, o.x));
                float x = std::clamp(thetaO / (0.5f * kPi) * res.thetaO - 0.5f, 0.0f, float(res.thetaO - 1));
                float y = std::clamp(phi / kPi * res.phi - 0.5f, 0.0f, float(res.phi - 1));
                int x0 = std::min(int(x), std::max(res.thetaO - 2, 0)), y0 = std::min(int(y), std::max(res.phi - 2, 0));
                float fx = std::min(x - x0, 1.0f), fy = std::min(y - y0, 1.0f);
                float w = weight * invBase;
                uint32_t i00 = uint32_t(x0 * res.phi + y0), i10 = i00 + uint32_t(res.phi);
                taps.push_back({i00, w * (1 - fx) * (1 - fy)});
                taps.push_back({i00 + 1, w * (1 - fx) * fy});
                taps.push_back({i10, w * fx * (1 - fy)});
                taps.push_back({i10 + 1, w * fx * fy});
            });
            for (int ti = 0; ti < res.thetaI; ++ti) {
                const float* row = base.values.data() + size_t(ti) * slice;
                double v = 0.0;
                for (const auto& [index, w] : taps) v += double(w) * row[index];
                out.values[size_t(ti) * slice + size_t(to) * res.phi + p] = std::min(float(v), 1.0f);
            }
        }
    });
    return out;
}

}  // namespace glimmer::wang2020
