// A scene uploaded to the GPU: one vertex/index buffer pair per mesh, material and light buffers, textures.
// Each mesh's index buffer is split into spatial chunks (render/mesh_chunks.h) that are culled against the view
// frustum per draw; single-sided materials cull back faces.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "gl/handles.h"
#include "render/mesh_chunks.h"
#include "scene/scene.h"

namespace glimmer {

class GpuScene {
public:
    explicit GpuScene(const Scene& scene);

    // Re-uploads materials and lights (after parameter edits); geometry stays.
    void updateMaterialsAndLights(const Scene& scene);
    // Draws every instance with the bound G-buffer program (sets per-draw uniforms at locations 0-4): the chunks
    // whose bounds intersect the frustum of `viewProjection`, back faces culled on single-sided materials (the
    // winding flipped for mirroring transforms). Sets GL_CULL_FACE / glFrontFace per draw and leaves culling off.
    // `normalMatrix` false: location 1 is not set (depth-only programs such as the shadow maps' have no normals).
    void drawInstances(const Scene& scene, const glm::mat4& viewProjection, bool normalMatrix = true) const;
    int lightCount() const { return lightCount_; }
    // Mesh-space chunks of a mesh (bounds for culling and for the shadow maps' scene bounds).
    const std::vector<MeshChunk>& meshChunks(uint32_t mesh) const { return meshes_[mesh].chunks; }
    size_t meshCount() const { return meshes_.size(); }
    // Unique for the lifetime of the process (never reused by a later GpuScene): caches of rendered geometry
    // (shadow maps) key on it.
    uint64_t id() const { return id_; }

    struct DrawStats {
        size_t chunksTotal = 0, chunksDrawn = 0;
        size_t trianglesTotal = 0, trianglesDrawn = 0;
    };
    // Counts of the last drawInstances call (for --stats).
    const DrawStats& lastDrawStats() const { return drawStats_; }

private:
    struct MeshBuffers {
        gl::VertexArray vao;
        gl::Buffer vertices, indices;
        GLsizei indexCount = 0;
        std::vector<MeshChunk> chunks;
    };
    std::vector<MeshBuffers> meshes_;
    std::vector<gl::Texture> textures_;
    gl::Buffer materials_, lights_;
    int lightCount_ = 0;
    uint64_t id_ = 0;
    mutable DrawStats drawStats_;
    mutable std::vector<GLsizei> drawCounts_;       // per-draw scratch for glMultiDrawElements
    mutable std::vector<const void*> drawOffsets_;
};

}  // namespace glimmer
