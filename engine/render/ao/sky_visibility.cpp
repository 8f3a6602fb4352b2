#include "render/ao/sky_visibility.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <mutex>
#include <sstream>
#include <thread>

#include "core/cache_file.h"
#include "core/clock.h"
#include "core/log.h"

namespace glimmer::ao {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kInvalidFraction = 0.25f;   // back-face hits beyond this fraction of cast rays: inside a solid
constexpr uint32_t kLayoutVersion = 1;      // bump when the payload or the bake changes

uint64_t splitMix(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// Fibonacci lattice on the sphere: nearly uniform, deterministic, symmetric about the horizon.
std::vector<glm::vec3> fibonacciDirections(int count) {
    std::vector<glm::vec3> d;
    const float golden = kPi * (3.0f - std::sqrt(5.0f));
    for (int i = 0; i < count; ++i) {
        float y = 1.0f - (float(i) + 0.5f) * 2.0f / float(count);
        float r = std::sqrt(std::max(0.0f, 1.0f - y * y));
        d.push_back({r * std::cos(golden * float(i)), y, r * std::sin(golden * float(i))});
    }
    return d;
}

glm::vec4 bakeProbe(const SceneRays& rays, glm::vec3 position, const std::vector<glm::vec3>& directions,
                    float rotation, float maxDistance) {
    const float c = std::cos(rotation), s = std::sin(rotation);
    float sumV = 0.0f;
    glm::vec3 sumVw(0.0f);
    int cast = 0, backFaces = 0;
    for (glm::vec3 d : directions) {
        glm::vec3 w(c * d.x - s * d.z, d.y, s * d.x + c * d.z);   // rotation about +y keeps the horizon split
        float visible = 1.0f;                                       // below the horizon: the environment's ground
        if (w.y > 0.0f) {
            RayHit hit = rays.cast(position, w, 0.0f, maxDistance);
            ++cast;
            if (hit.hit) {
                visible = 0.0f;
                backFaces += hit.backFace;
            }
        }
        sumV += visible;
        sumVw += visible * w;
    }
    if (cast > 0 && float(backFaces) > kInvalidFraction * float(cast)) return glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f);
    const float n = float(directions.size());
    return glm::vec4(sumV / n, 3.0f * sumVw / n);
}

std::string geometryHash(const WorldTriangles& triangles) {
    std::string bytes(reinterpret_cast<const char*>(triangles.positions.data()),
                      triangles.positions.size() * sizeof(glm::vec3));
    bytes.append(reinterpret_cast<const char*>(triangles.indices.data()), triangles.indices.size() * sizeof(uint32_t));
    bytes.append(reinterpret_cast<const char*>(triangles.frontNormals.data()),
                 triangles.frontNormals.size() * sizeof(glm::vec3));
    return cache::contentHash(bytes);
}

constexpr size_t kHeaderBytes = 3 * sizeof(int32_t) + 4 * sizeof(float);

std::string encode(const SkyVisibilityGrid& grid) {
    std::string out(kHeaderBytes + grid.probes.size() * sizeof(glm::vec4), '\0');
    int32_t dims[3] = {grid.dims.x, grid.dims.y, grid.dims.z};
    float frame[4] = {grid.origin.x, grid.origin.y, grid.origin.z, grid.cellSize};
    std::memcpy(out.data(), dims, sizeof(dims));
    std::memcpy(out.data() + sizeof(dims), frame, sizeof(frame));
    std::memcpy(out.data() + kHeaderBytes, grid.probes.data(), grid.probes.size() * sizeof(glm::vec4));
    return out;
}

// Values a bake can produce: finite, a in {-1} or [0, 1], |b| <= 3.
bool plausible(const SkyVisibilityGrid& layout, std::string_view payload) {
    int32_t dims[3];
    float frame[4];
    std::memcpy(dims, payload.data(), sizeof(dims));
    std::memcpy(frame, payload.data() + sizeof(dims), sizeof(frame));
    if (dims[0] != layout.dims.x || dims[1] != layout.dims.y || dims[2] != layout.dims.z) return false;
    if (frame[0] != layout.origin.x || frame[1] != layout.origin.y || frame[2] != layout.origin.z ||
        frame[3] != layout.cellSize)
        return false;
    const size_t count = (payload.size() - kHeaderBytes) / sizeof(glm::vec4);
    for (size_t i = 0; i < count; ++i) {
        glm::vec4 p;
        std::memcpy(&p, payload.data() + kHeaderBytes + i * sizeof(glm::vec4), sizeof(p));
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w)) return false;
        if (!(p.x == -1.0f || (p.x >= 0.0f && p.x <= 1.0f))) return false;
        if (glm::length(glm::vec3(p.y, p.z, p.w)) > 3.0f + 1e-4f) return false;
    }
    return true;
}

}  // namespace

std::string SkyVisibilityParams::text() const {
    std::ostringstream out;
    out << "cell=" << cellSize << " directions=" << directions << " seed=" << seed << " ground=visible"
        << " invalid>" << kInvalidFraction;
    return out.str();
}

size_t SkyVisibilityGrid::validCount() const {
    return size_t(std::count_if(probes.begin(), probes.end(), [](const glm::vec4& p) { return p.x >= 0.0f; }));
}

float SkyVisibilityGrid::evaluate(glm::vec3 position, glm::vec3 normal) const {
    if (probes.empty()) return 1.0f;
    // Mirrors shaders/ao/sky_visibility.glsl.
    glm::vec3 q = position + normal * (0.5f * cellSize);
    glm::vec3 g = (q - origin) / cellSize - 0.5f;
    glm::vec3 base = glm::floor(g), f = g - base;
    glm::vec4 sum(0.0f);
    float weightSum = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
        glm::ivec3 offset(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        glm::ivec3 i = glm::clamp(glm::ivec3(base) + offset, glm::ivec3(0), dims - 1);
        glm::vec4 probe = probes[(size_t(i.z) * dims.y + i.y) * dims.x + i.x];
        if (probe.x < 0.0f) continue;
        glm::vec3 t = glm::mix(1.0f - f, f, glm::vec3(offset));
        glm::vec3 toProbe = probePosition(i) - position;
        float len = glm::length(toProbe);
        float facing = len > 1e-6f ? 0.5f * (glm::dot(toProbe / len, normal) + 1.0f) : 1.0f;
        float w = t.x * t.y * t.z * (facing * facing + 0.2f);
        sum += w * probe;
        weightSum += w;
    }
    if (weightSum < 1e-5f) return 1.0f;
    sum /= weightSum;
    return glm::clamp(sum.x + (2.0f / 3.0f) * glm::dot(glm::vec3(sum.y, sum.z, sum.w), normal), 0.0f, 1.0f);
}

SkyVisibilityGrid gridLayout(const WorldTriangles& triangles, const SkyVisibilityParams& params) {
    SkyVisibilityGrid grid;
    if (triangles.triangleCount() == 0) return grid;
    glm::vec3 extent = triangles.boundsMax - triangles.boundsMin;
    float largest = std::max({extent.x, extent.y, extent.z});
    grid.cellSize = std::max(params.cellSize, largest / float(kMaxProbesPerAxis - 2));
    grid.origin = triangles.boundsMin - grid.cellSize;
    grid.dims = glm::max(glm::ivec3(glm::ceil((extent + 2.0f * grid.cellSize) / grid.cellSize)), glm::ivec3(1));
    grid.dims = glm::min(grid.dims, glm::ivec3(kMaxProbesPerAxis));
    return grid;
}

SkyVisibilityGrid bakeSkyVisibility(const WorldTriangles& triangles, const SkyVisibilityParams& params, int threads,
                                    const std::function<void(double)>& progress) {
    SkyVisibilityGrid grid = gridLayout(triangles, params);
    if (grid.dims.x == 0) return grid;
    SceneRays rays(triangles);
    const std::vector<glm::vec3> directions = fibonacciDirections(params.directions);
    const glm::vec3 extent = triangles.boundsMax - triangles.boundsMin + 2.0f * grid.cellSize;
    const float maxDistance = 2.0f * glm::length(extent) + 1.0f;   // anything farther is outside the scene
    const size_t count = size_t(grid.dims.x) * grid.dims.y * grid.dims.z;
    grid.probes.assign(count, glm::vec4(0.0f));
    const int rows = grid.dims.y * grid.dims.z;
    const int workers = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    std::atomic<int> next{0}, done{0};
    std::mutex progressMutex;
    int reportedTenth = 0;
    std::vector<std::thread> pool;
    for (int t = 0; t < workers; ++t)
        pool.emplace_back([&] {
            for (int row = next++; row < rows; row = next++) {
                const int y = row % grid.dims.y, z = row / grid.dims.y;
                for (int x = 0; x < grid.dims.x; ++x) {
                    const size_t index = (size_t(z) * grid.dims.y + y) * grid.dims.x + x;
                    const float rotation = float(splitMix(index ^ (uint64_t(params.seed) << 40)) >> 40) /
                                           float(1u << 24) * 2.0f * kPi;
                    grid.probes[index] = bakeProbe(rays, grid.probePosition({x, y, z}), directions, rotation, maxDistance);
                }
                const int finished = ++done;
                if (progress && finished * 10 / rows > reportedTenth) {
                    std::lock_guard<std::mutex> lock(progressMutex);
                    if (finished * 10 / rows > reportedTenth) {
                        reportedTenth = finished * 10 / rows;
                        progress(double(finished) / rows);
                    }
                }
            }
        });
    for (std::thread& t : pool) t.join();
    return grid;
}

std::string skyVisibilityCacheName(const WorldTriangles& triangles, const SkyVisibilityParams& params) {
    // Geometry and parameters both name the file, so bakes of other parameters do not evict each other.
    return "sky_visibility_" + cache::contentHash(geometryHash(triangles) + " " + params.text()) + ".bin";
}

SkyVisibilityResult loadOrBakeSkyVisibility(const Scene& scene, const SkyVisibilityParams& params,
                                            const std::filesystem::path& cacheDir, int threads) {
    Stopwatch clock;
    SkyVisibilityResult result;
    const WorldTriangles triangles = worldTriangles(scene);
    const SkyVisibilityGrid layout = gridLayout(triangles, params);
    if (layout.dims.x == 0) return result;
    const std::string hash = geometryHash(triangles);
    const std::string name = skyVisibilityCacheName(triangles, params);
    const cache::CacheKey key{"sky-visibility", kLayoutVersion,
                              "geometry=" + hash + " triangles=" + std::to_string(triangles.triangleCount()) + " " +
                                  params.text()};
    cache::CacheDir dir(cacheDir);
    result.cacheFile = dir.path() / name;
    const size_t count = size_t(layout.dims.x) * layout.dims.y * layout.dims.z;
    const uint64_t expected = kHeaderBytes + count * sizeof(glm::vec4);
    if (std::optional<std::string> bytes =
            dir.load(name, key, expected, [&](std::string_view p) { return plausible(layout, p); })) {
        result.grid = layout;
        result.grid.probes.resize(count);
        std::memcpy(result.grid.probes.data(), bytes->data() + kHeaderBytes, count * sizeof(glm::vec4));
        result.fromCache = result.cached = true;
        result.milliseconds = clock.elapsedMs();
        log::info("ao: sky visibility loaded from ", result.cacheFile.string(), " in ", result.milliseconds, " ms");
        return result;
    }
    const int workers = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
    log::info("ao: baking sky visibility of ", scene.name, " (", triangles.triangleCount(), " triangles, ",
              layout.dims.x, "x", layout.dims.y, "x", layout.dims.z, " probes every ", layout.cellSize, " m, ",
              params.directions / 2, " rays each, ", workers, " threads)");
    result.grid = bakeSkyVisibility(triangles, params, workers, [&](double fraction) {
        log::info("ao: sky visibility ", int(std::lround(fraction * 100.0)), "% (", clock.elapsedMs() / 1000.0, " s)");
    });
    result.cached = dir.store(name, key, encode(result.grid));
    result.milliseconds = clock.elapsedMs();
    log::info("ao: sky visibility baked in ", result.milliseconds, " ms, ", result.grid.validCount(), " of ", count,
              " probes valid", result.cached ? ", cached in " + result.cacheFile.string() : std::string(", not cached"));
    return result;
}

}  // namespace glimmer::ao
