// Large-scale ambient occlusion: how much of the sky a surface sees, baked once per static scene into a probe
// grid (docs/ambient_occlusion.md). The screen-space pass (GTAO, shaders/ao/gtao.frag) cannot see occluders off
// screen or beyond its radius, such as the 4 m deep roof of the atrium's arcades; this term can.
//
// - Probes sit at cell centres of a regular grid over the scene's bounds (padded by one cell). Each casts the
//   upper half of a fixed Fibonacci set of directions (rotated about +y by a per-probe angle from a fixed seed)
//   with Embree. Directions below the horizon count as visible: the environment's lower hemisphere already stands
//   for the ground, so only the sky is subject to this term (a wall in the open court keeps its ground light).
// - Each probe stores the visibility V(w) projected onto the first two SH bands, V ~ a + b.w (a = mean, b = 3 x the
//   first moment). A surface with normal n then sees the cosine-weighted visibility
//   (1/pi) int_{H(n)} V(w) (n.w) dw = a + (2/3) b.n, clamped to [0, 1].
// - Probes inside solids (more than a quarter of their rays meet back faces) are invalid (a < 0) and skipped when
//   interpolating; the lookup offsets the point along its normal by half a cell and weights the 8 probes around it
//   trilinearly times a wrap-shaped factor that favours probes in front of the surface (as in DDGI).
// - The result is cached on disk (core/cache_file.h) under a hash of the world-space geometry and the bake
//   parameters; a missing, stale, truncated or corrupt file is rebaked.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "render/ao/scene_rays.h"
#include "scene/scene.h"

namespace glimmer::ao {

struct SkyVisibilityParams {
    float cellSize = 0.5f;      // metres; grown when the scene would need more than kMaxProbesPerAxis per axis
    int directions = 128;       // Fibonacci directions on the whole sphere (half of them are cast)
    uint32_t seed = 1;          // per-probe rotation
    std::string text() const;   // for cache keys and messages
};
constexpr int kMaxProbesPerAxis = 128;

struct SkyVisibilityGrid {
    glm::ivec3 dims{0};
    glm::vec3 origin{0.0f};     // corner of probe (0,0,0)'s cell; probe i sits at origin + (i + 0.5) * cellSize
    float cellSize = 1.0f;
    std::vector<glm::vec4> probes;   // (a, b.x, b.y, b.z); a < 0: invalid (inside a solid)
    bool empty() const { return probes.empty(); }
    size_t validCount() const;
    glm::vec3 probePosition(glm::ivec3 i) const { return origin + (glm::vec3(i) + 0.5f) * cellSize; }
    // The cosine-weighted sky visibility at a surface point (the same lookup as shaders/ao/sky_visibility.glsl).
    float evaluate(glm::vec3 position, glm::vec3 normal) const;
};

// The grid's placement for a scene's bounds under `params`.
SkyVisibilityGrid gridLayout(const WorldTriangles& triangles, const SkyVisibilityParams& params);
// Bakes every probe on `threads` threads (0: all cores). `progress` (fraction done) is called from the workers,
// one at a time, at most about every 10%.
SkyVisibilityGrid bakeSkyVisibility(const WorldTriangles& triangles, const SkyVisibilityParams& params,
                                    int threads = 0, const std::function<void(double)>& progress = {});

struct SkyVisibilityResult {
    SkyVisibilityGrid grid;
    bool fromCache = false;
    bool cached = false;          // stored or loaded: the result is on disk
    double milliseconds = 0.0;    // bake or cache load (including the geometry hash)
    std::filesystem::path cacheFile;
};
// The cache file name and key for a scene's geometry under `params` (exposed for tests).
std::string skyVisibilityCacheName(const WorldTriangles& triangles, const SkyVisibilityParams& params);
// Loads the grid from `cacheDir` or bakes and stores it, logging progress and the time.
SkyVisibilityResult loadOrBakeSkyVisibility(const Scene& scene, const SkyVisibilityParams& params,
                                            const std::filesystem::path& cacheDir, int threads = 0);

}  // namespace glimmer::ao
