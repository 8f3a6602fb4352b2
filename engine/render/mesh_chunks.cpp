#include "render/mesh_chunks.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <numeric>

namespace glimmer {
namespace {

struct ChunkBuilder {
    const std::vector<uint32_t>& indices;
    const std::vector<glm::vec3>& positions;
    const std::vector<glm::vec3>& centroids;
    size_t maxTriangles;
    ChunkedIndices& out;

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
        std::vector<uint32_t> cached(chunk.size()), ordered(chunk.size());
        meshopt_optimizeVertexCache(cached.data(), chunk.data(), chunk.size(), positions.size());
        meshopt_optimizeOverdraw(ordered.data(), cached.data(), cached.size(), &positions[0].x, positions.size(),
                                 sizeof(glm::vec3), 1.05f);
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

// One simplified level of a chunk's triangles, in the mesh's vertex indices. The chunk's vertices are first
// compacted to a local array, so each call costs the chunk's size rather than the mesh's (meshoptimizer sizes
// its tables by the vertex count it is given).
std::vector<uint32_t> simplifyChunk(const uint32_t* indices, size_t indexCount, const std::vector<glm::vec3>& positions,
                                    size_t targetIndices, float& meshSpaceError) {
    std::vector<uint32_t> local(indexCount), toMesh;
    std::vector<glm::vec3> localPositions;
    std::vector<std::pair<uint32_t, uint32_t>> seen;   // (mesh vertex, local vertex), sorted for lookup
    seen.reserve(indexCount);
    for (size_t i = 0; i < indexCount; ++i) seen.push_back({indices[i], 0});
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end(), [](auto& a, auto& b) { return a.first == b.first; }), seen.end());
    for (size_t v = 0; v < seen.size(); ++v) {
        seen[v].second = uint32_t(v);
        toMesh.push_back(seen[v].first);
        localPositions.push_back(positions[seen[v].first]);
    }
    for (size_t i = 0; i < indexCount; ++i)
        local[i] = std::lower_bound(seen.begin(), seen.end(), std::pair{indices[i], 0u})->second;
    std::vector<uint32_t> simplified(indexCount);
    float relativeError = 0.0f;
    // Locked border: the chunk's open edges (its seams with neighbouring chunks and the mesh's own borders) keep
    // their vertices, so any two levels of neighbouring chunks share them exactly. Error unbounded here: the
    // target count sets the level, the draw chooses by the error reached.
    const float localScale = meshopt_simplifyScale(&localPositions[0].x, localPositions.size(), sizeof(glm::vec3));
    size_t count = meshopt_simplify(simplified.data(), local.data(), indexCount, &localPositions[0].x,
                                    localPositions.size(), sizeof(glm::vec3), targetIndices, 1.0f,
                                    meshopt_SimplifyLockBorder, &relativeError);
    simplified.resize(count);
    meshSpaceError = relativeError * localScale;
    std::vector<uint32_t> cached(count);
    if (count > 0) meshopt_optimizeVertexCache(cached.data(), simplified.data(), count, localPositions.size());
    for (uint32_t& index : cached) index = toMesh[index];
    return cached;
}

}  // namespace

void addChunkLods(ChunkedIndices& chunked, const std::vector<glm::vec3>& positions) {
    if (chunked.chunks.empty()) return;
    std::vector<bool> open(chunked.chunks.size(), true);   // a chunk that stopped simplifying gets no further level
    for (int level = 1; level <= kMaxCoarserLods; ++level) {
        for (size_t c = 0; c < chunked.chunks.size(); ++c) {
            MeshChunk& chunk = chunked.chunks[c];
            if (!open[c]) continue;
            const uint32_t previousCount = level == 1 ? chunk.indexCount : chunk.coarser[size_t(level - 2)].indexCount;
            const size_t target = std::max<size_t>(3, (size_t(chunk.indexCount / 3) >> (2 * level)) * 3);
            float error = 0.0f;
            std::vector<uint32_t> lod = simplifyChunk(chunked.indices.data() + chunk.firstIndex, chunk.indexCount,
                                                      positions, target, error);
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
