#include "render/mesh_chunks.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <numeric>

namespace glimmer {
namespace {

// A chunk's triangles over a local vertex array: meshoptimizer sizes its tables by the vertex count it is given,
// so every call on a chunk must see the chunk's vertices, not the mesh's (handing it the mesh's count made
// chunking quadratic: a 2048-cell plane ran past 120 s). Local indices keep the mesh's vertex order (a sorted,
// monotonic renumbering), so the optimisers' tie-breaking and results are those of the mesh-wide call.
struct LocalVertices {
    std::vector<uint32_t> indices;        // the chunk's triangles, local vertex numbers
    std::vector<uint32_t> toMesh;         // local vertex -> mesh vertex
    std::vector<glm::vec3> positions;     // of the local vertices
};

// `slot` is a scratch array over the mesh's vertices, all ~0u on entry and on return (so a chunk costs its own
// size, not the mesh's).
LocalVertices localVertices(const uint32_t* indices, size_t indexCount, const std::vector<glm::vec3>& positions,
                            std::vector<uint32_t>& slot) {
    LocalVertices local;
    for (size_t i = 0; i < indexCount; ++i)   // each vertex once (marked in `slot`), then in mesh order
        if (slot[indices[i]] == ~0u) {
            slot[indices[i]] = 0u;
            local.toMesh.push_back(indices[i]);
        }
    std::sort(local.toMesh.begin(), local.toMesh.end());
    local.positions.reserve(local.toMesh.size());
    for (size_t i = 0; i < local.toMesh.size(); ++i) {
        slot[local.toMesh[i]] = uint32_t(i);
        local.positions.push_back(positions[local.toMesh[i]]);
    }
    local.indices.resize(indexCount);
    for (size_t i = 0; i < indexCount; ++i) local.indices[i] = slot[indices[i]];
    for (uint32_t v : local.toMesh) slot[v] = ~0u;
    return local;
}

struct ChunkBuilder {
    const std::vector<uint32_t>& indices;
    const std::vector<glm::vec3>& positions;
    const std::vector<glm::vec3>& centroids;
    size_t maxTriangles;
    ChunkedIndices& out;
    std::vector<uint32_t> slot = std::vector<uint32_t>(positions.size(), ~0u);   // localVertices' scratch

    // Splits triangles [begin, end) of `order` at the median centroid along the longest axis of their centroids'
    // bounds until a range fits in one chunk.
    void split(std::vector<uint32_t>& order, size_t begin, size_t end) {
        if (end - begin <= maxTriangles) {
            emit(order, begin, end);
            return;
        }
        glm::vec3 lo(centroids[order[begin]]), hi(lo);
        for (size_t i = begin; i < end; ++i) {
            lo = glm::min(lo, centroids[order[i]]);
            hi = glm::max(hi, centroids[order[i]]);
        }
        glm::vec3 extent = hi - lo;
        int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        size_t mid = begin + (end - begin) / 2;
        std::nth_element(order.begin() + std::ptrdiff_t(begin), order.begin() + std::ptrdiff_t(mid),
                         order.begin() + std::ptrdiff_t(end),
                         [&](uint32_t a, uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
        split(order, begin, mid);
        split(order, mid, end);
    }

    void emit(const std::vector<uint32_t>& order, size_t begin, size_t end) {
        std::vector<uint32_t> chunk;
        chunk.reserve((end - begin) * 3);
        // Source order within the chunk (stable input for the optimisers, so the result is deterministic).
        std::vector<uint32_t> triangles(order.begin() + std::ptrdiff_t(begin), order.begin() + std::ptrdiff_t(end));
        std::sort(triangles.begin(), triangles.end());
        for (uint32_t t : triangles)
            for (int k = 0; k < 3; ++k) chunk.push_back(indices[size_t(t) * 3 + size_t(k)]);
        // Vertex cache first, then overdraw (meshoptimizer's overdraw pass expects vertex-cache-optimised input and
        // keeps its locality within the 1.05 threshold). Both only permute triangles and keep each one's winding.
        LocalVertices local = localVertices(chunk.data(), chunk.size(), positions, slot);
        std::vector<uint32_t> cached(chunk.size()), ordered(chunk.size());
        meshopt_optimizeVertexCache(cached.data(), local.indices.data(), local.indices.size(), local.positions.size());
        meshopt_optimizeOverdraw(ordered.data(), cached.data(), cached.size(), &local.positions[0].x,
                                 local.positions.size(), sizeof(glm::vec3), 1.05f);
        for (uint32_t& index : ordered) index = local.toMesh[index];
        MeshChunk c;
        c.firstIndex = uint32_t(out.indices.size());
        c.indexCount = uint32_t(ordered.size());
        c.boundsMin = c.boundsMax = positions[ordered[0]];
        for (uint32_t v : ordered) {
            c.boundsMin = glm::min(c.boundsMin, positions[v]);
            c.boundsMax = glm::max(c.boundsMax, positions[v]);
        }
        out.indices.insert(out.indices.end(), ordered.begin(), ordered.end());
        out.chunks.push_back(c);
    }
};

}  // namespace

ChunkedIndices buildMeshChunks(const std::vector<uint32_t>& indices, const std::vector<glm::vec3>& positions,
                               size_t maxTriangles) {
    ChunkedIndices out;
    size_t triangles = indices.size() / 3;
    if (triangles == 0 || positions.empty()) return out;
    std::vector<glm::vec3> centroids(triangles);
    for (size_t t = 0; t < triangles; ++t)
        centroids[t] = (positions[indices[3 * t]] + positions[indices[3 * t + 1]] + positions[indices[3 * t + 2]]) / 3.0f;
    std::vector<uint32_t> order(triangles);
    std::iota(order.begin(), order.end(), 0u);
    out.indices.reserve(triangles * 3);
    ChunkBuilder builder{indices, positions, centroids, std::max<size_t>(maxTriangles, 1), out};
    builder.split(order, 0, triangles);
    return out;
}

namespace {

// One simplified level of a chunk's triangles, in the mesh's vertex indices (over the chunk's own vertices, so
// each call costs the chunk's size rather than the mesh's).
std::vector<uint32_t> simplifyChunk(const uint32_t* indices, size_t indexCount, const std::vector<glm::vec3>& positions,
                                    size_t targetIndices, float& meshSpaceError, std::vector<uint32_t>& slot) {
    LocalVertices local = localVertices(indices, indexCount, positions, slot);
    std::vector<uint32_t> simplified(indexCount);
    float relativeError = 0.0f;
    // Locked border: the chunk's open edges (its seams with neighbouring chunks and the mesh's own borders) keep
    // their vertices, so any two levels of neighbouring chunks share them exactly. Error unbounded here: the
    // target count sets the level, the draw chooses by the error reached.
    const float localScale = meshopt_simplifyScale(&local.positions[0].x, local.positions.size(), sizeof(glm::vec3));
    size_t count = meshopt_simplify(simplified.data(), local.indices.data(), indexCount, &local.positions[0].x,
                                    local.positions.size(), sizeof(glm::vec3), targetIndices, 1.0f,
                                    meshopt_SimplifyLockBorder, &relativeError);
    simplified.resize(count);
    meshSpaceError = relativeError * localScale;
    std::vector<uint32_t> cached(count);
    if (count > 0) meshopt_optimizeVertexCache(cached.data(), simplified.data(), count, local.positions.size());
    for (uint32_t& index : cached) index = local.toMesh[index];
    return cached;
}

}  // namespace

void addChunkLods(ChunkedIndices& chunked, const std::vector<glm::vec3>& positions) {
    if (chunked.chunks.empty()) return;
    std::vector<bool> open(chunked.chunks.size(), true);   // a chunk that stopped simplifying gets no further level
    std::vector<uint32_t> slot(positions.size(), ~0u);
    for (int level = 1; level <= kMaxCoarserLods; ++level) {
        for (size_t c = 0; c < chunked.chunks.size(); ++c) {
            MeshChunk& chunk = chunked.chunks[c];
            if (!open[c]) continue;
            const uint32_t previousCount = level == 1 ? chunk.indexCount : chunk.coarser[size_t(level - 2)].indexCount;
            const size_t target = std::max<size_t>(3, (size_t(chunk.indexCount / 3) >> (2 * level)) * 3);
            float error = 0.0f;
            std::vector<uint32_t> lod = simplifyChunk(chunked.indices.data() + chunk.firstIndex, chunk.indexCount,
                                                      positions, target, error, slot);
            const float previousError = level == 1 ? 0.0f : chunk.coarser[size_t(level - 2)].error;
            if (lod.size() < 3 || lod.size() * 5 > size_t(previousCount) * 4 || !(error >= previousError)) {
                open[c] = false;
                continue;
            }
            ChunkLod& entry = chunk.coarser[size_t(level - 1)];
            entry.firstIndex = uint32_t(chunked.indices.size());
            entry.indexCount = uint32_t(lod.size());
            entry.error = error;
            chunk.coarserCount = level;
            chunked.indices.insert(chunked.indices.end(), lod.begin(), lod.end());
        }
    }
}

ChunkLod selectChunkLod(const MeshChunk& chunk, float allowedError, int& level) {
    level = 0;
    ChunkLod chosen{chunk.firstIndex, chunk.indexCount, 0.0f};
    for (int k = 0; k < chunk.coarserCount; ++k) {
        if (!(chunk.coarser[size_t(k)].error <= allowedError)) break;
        chosen = chunk.coarser[size_t(k)];
        level = k + 1;
    }
    return chosen;
}

bool boxOutsideFrustum(const glm::mat4& clipFromMesh, const glm::vec3& boundsMin, const glm::vec3& boundsMax) {
    // Count, per clip plane, the corners outside it; all 8 outside one plane culls the box.
    int outside[6] = {0, 0, 0, 0, 0, 0};
    for (int corner = 0; corner < 8; ++corner) {
        glm::vec3 p((corner & 1) ? boundsMax.x : boundsMin.x, (corner & 2) ? boundsMax.y : boundsMin.y,
                    (corner & 4) ? boundsMax.z : boundsMin.z);
        glm::vec4 c = clipFromMesh * glm::vec4(p, 1.0f);
        outside[0] += c.x < -c.w;
        outside[1] += c.x > c.w;
        outside[2] += c.y < -c.w;
        outside[3] += c.y > c.w;
        outside[4] += c.z < 0.0f;
        outside[5] += c.z > c.w;
    }
    for (int plane = 0; plane < 6; ++plane)
        if (outside[plane] == 8) return true;
    return false;
}

}  // namespace glimmer
