// Levels of detail of the mesh chunks (render/mesh_chunks.h addChunkLods, GpuScene, lod.pixel_error) and the
// lighting pass's shading classes (render/frame/lighting_pass.h, lighting.split_glinty):
//   - every coarser level of every atrium chunk has fewer triangles and no smaller error than the one before,
//     indexes only the chunk's own vertices, keeps every border edge of the chunk (so neighbouring chunks at
//     different levels meet without cracks), and stays within its stated error of the chunk's surface
//     (sampled points of the simplified triangles against the full-detail triangles);
//   - level 0 is the chunk itself, bit for bit;
//   - rendered: lod.pixel_error=1 draws under half the triangles of the court camera and moves few depth pixels
//     (silhouettes by at most about a pixel), pixel_error 8 moves more (the setting acts), 0 draws full detail;
//   - the split lighting gives the unsplit image (to float rounding) and its classes are exactly the glinty
//     pixels of the material AOV.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <map>
#include <set>

#include "offscreen/offscreen.h"
#include "render/aov.h"
#include "render/mesh_chunks.h"
#include "scene/builtin_scenes.h"
#include "scene/scene_loader.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(GeometryLod, GlContext);
GLIMMER_SUITE_NEEDS(LightingSplit, GlContext);

namespace glimmer {
namespace {

// Distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5, closest point by regions).
float pointTriangleDistance(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
    glm::vec3 bp = p - b;
    float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
    glm::vec3 cp = p - c;
    float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
    float va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
        return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    float denom = 1.0f / (va + vb + vc);
    return glm::length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

// Directed edges used by exactly one triangle whose reverse no triangle uses: the chunk's open border.
std::set<std::pair<uint32_t, uint32_t>> borderEdges(const uint32_t* indices, size_t count) {
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t t = 0; t + 2 < count; t += 3)
        for (int k = 0; k < 3; ++k) ++edges[{indices[t + k], indices[t + (k + 1) % 3]}];
    std::set<std::pair<uint32_t, uint32_t>> border;
    for (const auto& [e, n] : edges)
        if (n == 1 && !edges.count({e.second, e.first})) border.insert(e);
    return border;
}

TEST(GeometryLod, CoarserLevelsAreSmallerKeepTheirBordersAndStayWithinTheirError) {
    Scene atrium = makeBuiltinScene("atrium");
    size_t levels = 0, fullTriangles = 0, coarsestTriangles = 0;
    double worstErrorRatio = 0.0;
    for (const MeshData& mesh : atrium.meshes) {
        SCOPED_TRACE(mesh.name);
        ChunkedIndices chunked = buildMeshChunks(mesh.indices, mesh.positions);
        const ChunkedIndices plain = chunked;
        addChunkLods(chunked, mesh.positions);
        ASSERT_GE(chunked.indices.size(), plain.indices.size());
        EXPECT_TRUE(std::equal(plain.indices.begin(), plain.indices.end(), chunked.indices.begin()))
            << "level 0 is the chunked mesh unchanged";
        for (size_t c = 0; c < chunked.chunks.size(); ++c) {
            const MeshChunk& chunk = chunked.chunks[c];
            EXPECT_EQ(chunk.firstIndex, plain.chunks[c].firstIndex);
            EXPECT_EQ(chunk.indexCount, plain.chunks[c].indexCount);
            const uint32_t* full = chunked.indices.data() + chunk.firstIndex;
            std::set<uint32_t> ownVertices(full, full + chunk.indexCount);
            const auto border = borderEdges(full, chunk.indexCount);
            fullTriangles += chunk.indexCount / 3;
            uint32_t previousCount = chunk.indexCount;
            float previousError = 0.0f;
            for (int k = 0; k < chunk.coarserCount; ++k) {
                const ChunkLod& lod = chunk.coarser[size_t(k)];
                ++levels;
                ASSERT_LE(size_t(lod.firstIndex) + lod.indexCount, chunked.indices.size());
                ASSERT_GE(lod.firstIndex, plain.indices.size()) << "coarser levels follow every level 0 range";
                EXPECT_EQ(lod.indexCount % 3, 0u);
                EXPECT_LE(size_t(lod.indexCount) * 5, size_t(previousCount) * 4);
                EXPECT_GE(lod.error, previousError);
                const uint32_t* coarse = chunked.indices.data() + lod.firstIndex;
                for (uint32_t i = 0; i < lod.indexCount; ++i)
                    ASSERT_TRUE(ownVertices.count(coarse[i])) << "level " << k + 1 << " uses a vertex of another chunk";
                const auto coarseEdges = [&] {
                    std::set<std::pair<uint32_t, uint32_t>> e;
                    for (uint32_t t = 0; t + 2 < lod.indexCount; t += 3)
                        for (int j = 0; j < 3; ++j) e.insert({coarse[t + j], coarse[t + (j + 1) % 3]});
                    return e;
                }();
                for (const auto& e : border)
                    ASSERT_TRUE(coarseEdges.count(e)) << "level " << k + 1 << " lost border edge " << e.first << "-"
                                                      << e.second << " of chunk " << c;
                // Centroid and edge midpoints of each simplified triangle against the chunk's own triangles.
                float worst = 0.0f;
                for (uint32_t t = 0; t + 2 < lod.indexCount; t += 3) {
                    glm::vec3 a = mesh.positions[coarse[t]], b = mesh.positions[coarse[t + 1]],
                              d = mesh.positions[coarse[t + 2]];
                    for (glm::vec3 p : {(a + b + d) / 3.0f, 0.5f * (a + b), 0.5f * (b + d), 0.5f * (d + a)}) {
                        float nearest = 1e30f;
                        for (uint32_t u = 0; u + 2 < chunk.indexCount && nearest > 0.0f; u += 3)
                            nearest = std::min(nearest, pointTriangleDistance(p, mesh.positions[full[u]],
                                                                              mesh.positions[full[u + 1]],
                                                                              mesh.positions[full[u + 2]]));
                        worst = std::max(worst, nearest);
                    }
                }
                // meshoptimizer's error is a quadric estimate, not a bound: allowed 2x and 1 mm.
                EXPECT_LE(worst, 2.0f * lod.error + 1e-3f) << "level " << k + 1 << " of chunk " << c;
                if (lod.error > 1e-4f) worstErrorRatio = std::max(worstErrorRatio, double(worst / lod.error));
                previousCount = lod.indexCount;
                previousError = lod.error;
            }
            coarsestTriangles += (chunk.coarserCount ? chunk.coarser[size_t(chunk.coarserCount - 1)].indexCount
                                                     : chunk.indexCount) / 3;
        }
    }
    std::printf("  atrium: %zu coarser levels; %zu triangles at full detail, %zu at the coarsest levels; "
                "worst sampled distance / stated error %.2f\n",
                levels, fullTriangles, coarsestTriangles, worstErrorRatio);
    EXPECT_GT(levels, 50u);
    EXPECT_LT(coarsestTriangles * 4, fullTriangles) << "the coarsest levels keep under a quarter of the triangles";
}

RenderRequest courtRequest(int width, int height) {
    RenderRequest r;
    r.scene = "atrium";
    r.camera = "court";
    r.width = width;
    r.height = height;
    r.settings.method = "deliot2023";
    r.settings.apply("probes.enabled=0");   // the probes' capture costs seconds and changes nothing tested here
    return r;
}

// Pixels whose depth (AOV, distance to the eye) differs by more than 2% between two renders, sky included.
size_t movedDepthPixels(const RenderResult& a, const RenderResult& b) {
    size_t moved = 0;
    for (size_t i = 0; i < a.hdr.size(); i += 4) {
        bool skyA = a.hdr[i + 3] <= 0.0f, skyB = b.hdr[i + 3] <= 0.0f;
        if (skyA != skyB) { ++moved; continue; }
        if (!skyA && std::abs(a.hdr[i] - b.hdr[i]) > 0.02f * std::min(a.hdr[i], b.hdr[i])) ++moved;
    }
    return moved;
}

TEST(GeometryLod, CourtAtOnePixelErrorDrawsUnderHalfTheTrianglesAndMovesFewPixels) {
    RenderRequest request = courtRequest(320, 180);
    request.settings.debugView = findAov("depth").viewId;
    OffscreenSession session(request);
    RenderResult full = session.render(request);
    RenderRequest one = request, eight = request;
    one.settings.apply("lod.pixel_error=1");
    eight.settings.apply("lod.pixel_error=8");
    RenderResult atOne = session.render(one), atEight = session.render(eight);
    const auto drawn = [](const RenderResult& r) { return r.stats["gbuffer_draw"]["triangles_drawn"].get<size_t>(); };
    const size_t pixels = full.hdr.size() / 4;
    const size_t movedOne = movedDepthPixels(full, atOne), movedEight = movedDepthPixels(full, atEight);
    std::printf("  court 320x180: triangles %zu full, %zu at 1 px (%zu chunks simplified), %zu at 8 px; depth "
                "pixels moved: %zu (%.2f%%) at 1 px, %zu at 8 px\n",
                drawn(full), drawn(atOne), atOne.stats["gbuffer_draw"]["chunks_simplified"].get<size_t>(),
                drawn(atEight), movedOne, 100.0 * double(movedOne) / double(pixels), movedEight);
    EXPECT_EQ(full.stats["gbuffer_draw"]["chunks_simplified"].get<size_t>(), 0u);
    EXPECT_EQ(drawn(full), full.stats["gbuffer_draw"]["triangles_full_detail"].get<size_t>());
    EXPECT_LT(drawn(atOne) * 2, drawn(full));
    EXPECT_LE(drawn(atEight), drawn(atOne));
    EXPECT_LT(movedOne, pixels / 100) << "a one-pixel error moves silhouettes by about a pixel at most";
    EXPECT_GT(movedEight, movedOne) << "a larger allowed error must change more";
}

TEST(LightingSplit, SplitEqualsUnsplitAndItsClassesAreTheGlintyPixels) {
    RenderRequest request = courtRequest(192, 108);
    OffscreenSession session(request);
    Scene scene = loadScene(request.scene);
    RenderRequest ids = request;
    ids.settings.debugView = findAov("material").viewId;
    RenderResult material = session.render(ids);
    RenderResult unsplit = session.render(request);
    RenderRequest split = request;
    split.settings.apply("lighting.split_glinty=1");
    RenderResult splitResult = session.render(split);

    // The classes of the last (split) frame.
    session.context().makeCurrent();
    const GLuint shadingClass = session.renderer().resources().get(FrameResource::ShadingClass).texture();
    std::vector<float> classes(size_t(request.width) * request.height);
    glGetTextureImage(shadingClass, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      GLsizei(classes.size() * sizeof(float)), classes.data());
    size_t glinty = 0, mismatched = 0;
    for (size_t i = 0; i < classes.size(); ++i) {
        size_t id = size_t(std::lround(material.hdr[i * 4 + 2]));
        bool expected = material.hdr[i * 4 + 3] > 0.0f && id < scene.materials.size() && scene.materials[id].glinty;
        glinty += expected;
        mismatched += (classes[i] == 1.0f) != expected || (classes[i] != 0.0f && classes[i] != 1.0f);
    }
    EXPECT_GT(glinty, classes.size() / 20) << "the court view shows glint materials";
    EXPECT_LT(glinty, classes.size() * 9 / 10) << "and other materials";
    EXPECT_EQ(mismatched, 0u);

    double worst = 0.0;
    size_t differing = 0;
    for (size_t i = 0; i < unsplit.hdr.size(); ++i) {
        double a = unsplit.hdr[i], b = splitResult.hdr[i];
        double relative = std::abs(a - b) / std::max(1e-3, std::abs(a));
        worst = std::max(worst, relative);
        differing += a != b;
    }
    std::printf("  split lighting: %zu glinty pixels of %zu; HDR values differing %zu, worst relative %.2e\n",
                glinty, classes.size(), differing, worst);
    EXPECT_LT(worst, 1e-5) << "each pixel must be shaded by the program of its class with the same terms";
    EXPECT_EQ(splitResult.stats["counts"]["non_finite_values"].get<size_t>(), 0u);
}

// A shader's text with its quoted includes (shaders/ is the include root; macro includes such as
// GLINT_METHOD_FILE are left out), each file once.
std::string withIncludes(const std::filesystem::path& root, const std::string& file, std::set<std::string>& seen) {
    if (!seen.insert(file).second) return {};
    std::ifstream in(root / file);
    EXPECT_TRUE(in.good()) << file;
    std::string text, line;
    while (std::getline(in, line)) {
        size_t open = line.find("#include \"");
        if (open != std::string::npos) {
            size_t close = line.find('"', open + 10);
            text += withIncludes(root, line.substr(open + 10, close - open - 10), seen);
        } else {
            text += line + "\n";
        }
    }
    return text;
}

// With lighting.split_glinty each pixel passes the GL_EQUAL depth test of one lighting program only. A fragment
// shader with side effects (the method output check's atomics) runs before its depth test unless it declares early
// fragment tests, and then every pixel paid for both programs: the court's lighting pass took 2.2x as long. No
// query tells: llvmpipe counts GL_FRAGMENT_SHADER_INVOCATIONS before its depth test either way (+2.2 per pixel
// for the split with and without the declaration), so the source is what this reads.
TEST(LightingSplit, LightingShaderTestsDepthBeforeItsSideEffects) {
    const std::filesystem::path root = std::filesystem::path(GLIMMER_SOURCE_DIR) / "shaders";
    std::set<std::string> seen;
    const std::string text = withIncludes(root, "frame/lighting.frag", seen);
    const bool sideEffects = text.find("atomicAdd(") != std::string::npos || text.find("imageStore(") != std::string::npos;
    EXPECT_TRUE(sideEffects) << "the method output check's atomics are in the lighting shader";
    EXPECT_NE(text.find("layout(early_fragment_tests) in;"), std::string::npos)
        << "frame/lighting.frag has side effects: without early fragment tests both split programs shade every pixel";
}

}  // namespace
}  // namespace glimmer
