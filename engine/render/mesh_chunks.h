// Spatial chunks of a mesh's triangles, for per-chunk view-frustum culling at draw time (GpuScene).
// Triangles are split top-down at the median of their centroids along the longest axis (a BVH build whose leaves
// are the chunks) until a chunk holds at most `maxTriangles`; each chunk is then one contiguous range of the
// index buffer, reordered by meshoptimizer for the post-transform vertex cache and then for overdraw.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace glimmer {

struct MeshChunk {
    uint32_t firstIndex = 0;   // into ChunkedIndices::indices
    uint32_t indexCount = 0;   // 3 per triangle
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};   // of the chunk's vertices, mesh space
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

// True when the box (mesh space) lies entirely outside one plane of the clip volume of `clipFromMesh`
// (x, y in [-w, w], z in [0, w]: glClipControl(..., GL_ZERO_TO_ONE)). Conservative: a box that is not culled may
// still be invisible, a culled box never covers a pixel.
bool boxOutsideFrustum(const glm::mat4& clipFromMesh, const glm::vec3& boundsMin, const glm::vec3& boundsMax);

}  // namespace glimmer
