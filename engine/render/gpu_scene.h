// A scene uploaded to the GPU: one vertex/index buffer pair per mesh, material and light buffers, textures.
#pragma once
#include <vector>

#include "gl/handles.h"
#include "scene/scene.h"

namespace glimmer {

class GpuScene {
public:
    explicit GpuScene(const Scene& scene);

    // Re-uploads materials and lights (after parameter edits); geometry stays.
    void updateMaterialsAndLights(const Scene& scene);
    // Draws every instance with the bound G-buffer program (sets per-draw uniforms at locations 0-4).
    void drawInstances(const Scene& scene) const;
    int lightCount() const { return lightCount_; }

private:
    struct MeshBuffers {
        gl::VertexArray vao;
        gl::Buffer vertices, indices;
        GLsizei indexCount = 0;
    };
    std::vector<MeshBuffers> meshes_;
    std::vector<gl::Texture> textures_;
    gl::Buffer materials_, lights_;
    int lightCount_ = 0;
};

}  // namespace glimmer
