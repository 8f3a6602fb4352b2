// Geometry work of the G-buffer pass (render/mesh_chunks.h, GpuScene): spatial chunks keep every triangle once
// with its winding, chunk bounds hold their vertices, the frustum test never culls a box with a visible point
// (checked against sampled points of the box), and the atrium's single-sided materials change no pixel of any
// camera compared with all materials two-sided (no surface disappears).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "offscreen/offscreen.h"
#include "render/aov.h"
#include "render/mesh_chunks.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_loader.h"
#include "support/measure.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(GeometryCulling, GlContext);

namespace glimmer {
namespace {
namespace fs = std::filesystem;

// A triangle as its indices rotated so the smallest comes first: equal keys mean same triangle, same winding.
std::array<uint32_t, 3> canonical(uint32_t a, uint32_t b, uint32_t c) {
    if (b < a && b < c) return {b, c, a};
    if (c < a && c < b) return {c, a, b};
    return {a, b, c};
}

std::map<std::array<uint32_t, 3>, int> triangleCounts(const std::vector<uint32_t>& indices) {
    std::map<std::array<uint32_t, 3>, int> counts;
    for (size_t i = 0; i + 2 < indices.size(); i += 3) ++counts[canonical(indices[i], indices[i + 1], indices[i + 2])];
    return counts;
}

TEST(GeometryChunks, EveryTriangleOnceWithItsWindingAndBoundsHoldTheChunk) {
    Scene atrium = makeBuiltinScene("atrium");
    size_t meshesSplit = 0;
    for (const MeshData& mesh : atrium.meshes) {
        SCOPED_TRACE(mesh.name);
        const size_t maxTriangles = 1000;
        ChunkedIndices chunked = buildMeshChunks(mesh.indices, mesh.positions, maxTriangles);
        EXPECT_EQ(triangleCounts(chunked.indices), triangleCounts(mesh.indices));
        size_t covered = 0;
        for (const MeshChunk& chunk : chunked.chunks) {
            EXPECT_EQ(chunk.firstIndex, covered) << "chunks are contiguous, in order";
            EXPECT_EQ(chunk.indexCount % 3, 0u);
            EXPECT_LE(chunk.indexCount / 3, maxTriangles);
            EXPECT_GT(chunk.indexCount, 0u);
            for (uint32_t i = chunk.firstIndex; i < chunk.firstIndex + chunk.indexCount; ++i) {
                glm::vec3 p = mesh.positions[chunked.indices[i]];
                ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, chunk.boundsMin)) &&
                            glm::all(glm::lessThanEqual(p, chunk.boundsMax)));
            }
            covered += chunk.indexCount;
        }
        EXPECT_EQ(covered, mesh.indices.size());
        size_t triangles = mesh.indices.size() / 3;
        EXPECT_GE(chunked.chunks.size(), (triangles + maxTriangles - 1) / maxTriangles);
        // A median split makes at most twice the minimum number of leaves.
        EXPECT_LE(chunked.chunks.size(), 2 * ((triangles + maxTriangles - 1) / maxTriangles) + 1);
        meshesSplit += chunked.chunks.size() > 1;
    }
    EXPECT_GE(meshesSplit, 3u) << "floor, walls and stonework are larger than one chunk";
}

TEST(GeometryChunks, SpatialSplitMakesCompactChunks) {
    // A 64 x 64 grid of unit quads on y = 0: chunks of 512 triangles must be compact (a 16 x 16 block has a
    // 256 m^2 box; a strip of rows would span the whole grid).
    MeshData grid;
    const int n = 64;
    for (int z = 0; z <= n; ++z)
        for (int x = 0; x <= n; ++x) grid.positions.push_back({float(x), 0.0f, float(z)});
    for (int z = 0; z < n; ++z)
        for (int x = 0; x < n; ++x) {
            uint32_t a = uint32_t(z * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
            grid.indices.insert(grid.indices.end(), {a, c, b, b, c, d});
        }
    ChunkedIndices chunked = buildMeshChunks(grid.indices, grid.positions, 512);
    EXPECT_EQ(chunked.chunks.size(), 16u);
    for (const MeshChunk& chunk : chunked.chunks) {
        glm::vec3 e = chunk.boundsMax - chunk.boundsMin;
        EXPECT_LE(e.x * e.z, 17.0f * 17.0f) << "chunk box " << e.x << " x " << e.z;
    }
}

TEST(GeometryChunks, FrustumTestNeverCullsABoxWithAVisiblePoint) {
    Camera camera;
    camera.position = {0.0f, 1.0f, 5.0f};
    camera.target = {0.0f, 1.0f, 0.0f};
    camera.verticalFovDegrees = 60.0f;
    glm::mat4 clipFromWorld = camera.projection(16.0f / 9.0f) * camera.view();
    std::mt19937 rng(1234);
    std::uniform_real_distribution<float> centre(-12.0f, 12.0f), size(0.05f, 4.0f), unit(0.0f, 1.0f);
    int culled = 0, kept = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        glm::vec3 c(centre(rng), centre(rng), centre(rng)), h(size(rng), size(rng), size(rng));
        glm::vec3 lo = c - h, hi = c + h;
        bool outside = boxOutsideFrustum(clipFromWorld, lo, hi);
        (outside ? culled : kept) += 1;
        if (!outside) continue;
        // No point of a culled box may land inside the clip volume.
        for (int s = 0; s < 200; ++s) {
            glm::vec3 p = lo + (hi - lo) * glm::vec3(unit(rng), unit(rng), unit(rng));
            glm::vec4 q = clipFromWorld * glm::vec4(p, 1.0f);
            bool inside = q.w > 0.0f && std::abs(q.x) <= q.w && std::abs(q.y) <= q.w && q.z >= 0.0f && q.z <= q.w;
            ASSERT_FALSE(inside) << "trial " << trial;
        }
    }
    EXPECT_GT(culled, 1000) << "boxes behind and beside the camera are culled";
    EXPECT_GT(kept, 200);
    // The obvious cases.
    EXPECT_FALSE(boxOutsideFrustum(clipFromWorld, {-0.5f, 0.5f, -0.5f}, {0.5f, 1.5f, 0.5f}));      // ahead
    EXPECT_TRUE(boxOutsideFrustum(clipFromWorld, {-0.5f, 0.5f, 8.0f}, {0.5f, 1.5f, 9.0f}));        // behind
    EXPECT_TRUE(boxOutsideFrustum(clipFromWorld, {40.0f, 0.5f, -1.0f}, {41.0f, 1.5f, 0.0f}));      // far right
    EXPECT_FALSE(boxOutsideFrustum(clipFromWorld, {-50.0f, -50.0f, -50.0f}, {50.0f, 50.0f, 50.0f}));  // around
}

// The atrium with all materials two-sided, as a scene file on top of content/atrium.json.
fs::path twoSidedAtrium() {
    fs::path dir = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "culling";
    fs::create_directories(dir);
    nlohmann::json doc;
    std::ifstream(fs::path(GLIMMER_SOURCE_DIR) / "content" / "atrium.json") >> doc;
    for (const Material& m : makeBuiltinScene("atrium").materials)
        doc["materials"].push_back({{"name", m.name}, {"doubleSided", true}});
    fs::path path = dir / "atrium_two_sided.json";
    std::ofstream(path) << doc.dump(2);
    return path;
}

TEST(GeometryCulling, AtriumSingleSidedMaterialsHideNoSurfaceFromAnyCamera) {
    Scene atrium = loadScene("atrium");
    size_t singleSided = 0;
    for (const Material& m : atrium.materials) singleSided += !m.doubleSided;
    EXPECT_GE(singleSided, 4u);
    for (const Material& m : loadScene(twoSidedAtrium().string()).materials) EXPECT_TRUE(m.doubleSided) << m.name;
    // Normals view: a surface that vanished would show what is behind it (another normal or the background) over
    // its whole area. Culling only removes back faces, so a pixel can change only where the two-sided render
    // showed a back face: at the shared edges of closed solids, where a back face ties with the front face
    // rasterised beside it (measured: 0 to 8 pixels of 20,736 per camera). Those pixels may differ, nothing more.
    // Both views from one session per scene (a session bakes the scene's sky visibility and shadow maps once).
    // CI: three of the seven cameras (objects: the close view whose triangle count is asserted; overview: the most
    // surfaces at once; grazing: the floor edge-on, where back faces tie with front faces at the tiles' edges);
    // GLIMMER_MEASURE=1: every camera. Each camera costs four renders (two scenes, two views).
    std::vector<Camera> cameras;
    for (const Camera& camera : atrium.cameras)
        if (test::fullMeasurement() || camera.name == "objects" || camera.name == "overview" || camera.name == "grazing")
            cameras.push_back(camera);
    ASSERT_EQ(cameras.size(), test::fullMeasurement() ? atrium.cameras.size() : 3u);
    const std::vector<const char*> aovs = {"normal", "final"};
    auto renderAll = [&](const std::string& scene) {
        RenderRequest r;
        r.scene = scene;
        r.width = 192;
        r.height = 108;
        r.environment = "none";
        std::vector<std::vector<RenderResult>> results(aovs.size());
        OffscreenSession session(r);   // one session at a time (each owns the EGL display while alive)
        for (size_t a = 0; a < aovs.size(); ++a) {
            r.settings.debugView = findAov(aovs[a]).viewId;
            for (const Camera& camera : cameras) {
                r.camera = camera.name;
                results[a].push_back(session.render(r));
            }
        }
        return results;
    };
    std::vector<std::vector<RenderResult>> culledAll = renderAll("atrium"), referenceAll = renderAll(twoSidedAtrium().string());
    for (size_t a = 0; a < aovs.size(); ++a) {
        const char* aov = aovs[a];
        const std::vector<RenderResult>&culled = culledAll[a], &reference = referenceAll[a];
        for (size_t c = 0; c < cameras.size(); ++c) {
            SCOPED_TRACE(std::string(aov) + " " + cameras[c].name);
            const RenderResult &ra = culled[c], &rb = reference[c];
            ASSERT_EQ(ra.display.size(), rb.display.size());
            size_t differing = 0, pixels = ra.display.size() / 4;
            for (size_t i = 0; i < pixels; ++i)
                differing += std::memcmp(&ra.display[4 * i], &rb.display[4 * i], 4) != 0;
            EXPECT_LE(differing, pixels / 1000);
            if (cameras[c].name == "objects")
                EXPECT_LT(ra.stats["gbuffer_draw"]["triangles_drawn"].get<size_t>(), atrium.triangleCount() * 3 / 4)
                    << "the objects camera sees less than three quarters of the triangles";
        }
    }
}

}  // namespace
}  // namespace glimmer
