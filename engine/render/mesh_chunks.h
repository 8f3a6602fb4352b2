// Spatial chunks of a mesh's triangles, for per-chunk view-frustum culling at draw time (GpuScene).
// Triangles are split top-down at the median of their centroids along the longest axis (a BVH build whose leaves
// are the chunks) until a chunk holds at most `maxTriangles`; each chunk is then one contiguous range of the
// index buffer, reordered by meshoptimizer for the post-transform vertex cache and then for overdraw.
// Levels of detail (addChunkLods): each chunk also gets up to kMaxCoarserLods simplified versions of its own
// triangles (meshoptimizer's edge-collapse simplifier, the chunk's border locked so that neighbouring chunks at
// different levels still meet without cracks), with the geometric error each one makes.
#pragma once
#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace glimmer {

// A simplified version of a chunk: its range of ChunkedIndices::indices and its error, the largest distance
// (mesh space) between the simplified surface and the chunk's own (meshoptimizer's estimate).
struct ChunkLod {
    uint32_t firstIndex = 0, indexCount = 0;
    float error = 0.0f;
};
constexpr int kMaxCoarserLods = 3;

struct MeshChunk {
    uint32_t firstIndex = 0;   // into ChunkedIndices::indices
    uint32_t indexCount = 0;   // 3 per triangle
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};   // of the chunk's vertices, mesh space
    // Coarser levels, each with fewer triangles and a larger error than the one before (coarserCount of them).
    std::array<ChunkLod, kMaxCoarserLods> coarser{};
    int coarserCount = 0;
};

struct ChunkedIndices {
    std::vector<uint32_t> indices;   // the mesh's triangles (each kept with its winding), chunk after chunk
    std::vector<MeshChunk> chunks;   // spatially coherent order (depth-first over the split tree)
};

// A few thousand triangles: small enough that the atrium's long meshes (floor, walls) split into parts a camera
// inside the court can cull, large enough that per-chunk draw overhead stays small next to the raster work.
constexpr size_t kDefaultChunkTriangles = 2048;

// `indices` must hold whole triangles indexing `positions`. An empty mesh gives no chunks.
ChunkedIndices buildMeshChunks(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions,
                               size_t maxTriangles = kDefaultChunkTriangles);

// Adds the coarser levels of every chunk: level k aims at 1 / 4^k of the chunk's triangles, and is kept only when
// it has at most 80% of the triangles of the level before. All chunks' level 1 ranges follow the level 0 ones
// in chunk order, then all level 2 ranges and so on, so the chunks a draw takes at one level stay adjacent.
void addChunkLods(ChunkedIndices& chunked, const std::vector<glm::vec3>& positions);

// The range to draw for a chunk when an error of `allowedError` (mesh space) is acceptable: the coarsest level
// whose error does not exceed it; level 0 (error 0) otherwise. `level` receives 0 .. coarserCount.
ChunkLod selectChunkLod(const MeshChunk& chunk, float allowedError, int& level);

// True when the box (mesh space) lies entirely outside one plane of the clip volume of `clipFromMesh`
// (x, y in [-w, w], z in [0, w]: glClipControl(..., GL_ZERO_TO_ONE)). Conservative: a box that is not culled may
// still be invisible, a culled box never covers a pixel.
bool boxOutsideFrustum(const glm::mat4& clipFromMesh, const glm::vec3& boundsMin, const glm::vec3& boundsMax);

}  // namespace glimmer
