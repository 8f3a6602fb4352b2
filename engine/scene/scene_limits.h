// Limits on what a model or scene file may ask for, far above any real model (Sponza: 0.3 M vertices, 260
// nodes; large photogrammetry scans: ~20 M vertices) and low enough that a hostile file fails in bounded time
// and memory instead of exhausting the machine. Stated for users in content/README.md and README.md.
#pragma once
#include <cstdint>

namespace glimmer {

constexpr uint64_t kMaxModelFileBytes = uint64_t(1) << 30;       // a .gltf / .glb file or one external buffer
constexpr uint64_t kMaxAccessorElements = uint64_t(1) << 26;     // 67 M elements per accessor
constexpr uint64_t kMaxZeroAccessorElements = uint64_t(1) << 24; // elements of an accessor without bufferView
constexpr uint64_t kMaxSceneVertices = uint64_t(1) << 27;        // over all meshes of one file
constexpr uint64_t kMaxSceneIndices = uint64_t(1) << 28;         // over all meshes of one file
constexpr uint64_t kMaxNodes = uint64_t(1) << 20;
constexpr int kMaxHierarchyDepth = 1024;
constexpr uint64_t kMaxInstances = uint64_t(1) << 20;            // mesh instances after expanding the node graph
constexpr uint64_t kMaxInstancedTriangles = uint64_t(1) << 30;   // triangles drawn per frame over all instances
constexpr uint64_t kMaxSceneFileBytes = uint64_t(64) << 20;      // a .json scene file
constexpr float kMaxCoordinate = 1e7f;                           // |x|, |y|, |z| of world positions, metres
constexpr float kMinCameraNear = 1e-5f, kMaxCameraNear = 1e3f;   // a camera's near plane, metres (scene files, glTF)

}  // namespace glimmer
