// A scene uploaded to the GPU: one vertex/index buffer pair per mesh, material and light buffers, textures.
// Each mesh's index buffer is split into spatial chunks (render/mesh_chunks.h) that are culled against the view
// frustum per draw; single-sided materials cull back faces.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "gl/handles.h"
#include "render/mesh_chunks.h"
#include "render/shader_interface.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace glimmer {

// Which instances a geometry pass draws: the G-buffer takes every material that is not blended; the emissive pass
// the non-blended emissive ones (again, depth-tested against the G-buffer's depth); blended materials are drawn
// by drawBlendedBackToFront only; depth-only programs (the shadow maps') the non-blended ones without setting the
// normal matrix (location 1), which they do not have: the alpha-masked materials (glTF MASK) and the others in
// separate draws, so that the others take a program without a fragment stage's work (no discard: the depth test
// runs before it; on llvmpipe 6x faster shadow maps).
enum class DrawSelection { Opaque, OpaqueEmissive, DepthOnlyUnmasked, DepthOnlyMasked };

// Level of detail for a draw (render/mesh_chunks.h): a chunk at distance d from `eye` (to its world-space bounding
// sphere; 0 inside it) is drawn at the coarsest level whose world-space error is at most d x errorPerDistance.
// errorPerDistance = 0 draws every chunk at full detail.
struct LodView {
    glm::vec3 eye{0.0f};
    float errorPerDistance = 0.0f;
};
// The LodView of a `heightPixels`-high image of `camera` that allows `maxPixelError` pixels of geometric error
// (an error e at distance d covers about e / d x heightPixels / (2 tan(fov / 2)) pixels). 0: full detail.
LodView lodViewFor(const Camera& camera, int heightPixels, float maxPixelError);

// A light as the shaders read it (shaders/common/frame.glsl GpuLight).
GpuLight gpuLight(const Light& light);

class GpuScene {
public:
    explicit GpuScene(const Scene& scene);

    // Re-uploads materials and lights (after parameter edits); geometry stays.
    void updateMaterialsAndLights(const Scene& scene);
    // Draws every instance with the bound G-buffer program (sets per-draw uniforms at locations 0-4): the chunks
    // whose bounds intersect the frustum of `viewProjection`, back faces culled on single-sided materials (the
    // winding flipped for mirroring transforms). Sets GL_CULL_FACE / glFrontFace per draw and leaves culling off.
    // `lod` picks each chunk's level of detail (passes that depth-test against the G-buffer pass the same one).
    void drawInstances(const Scene& scene, const glm::mat4& viewProjection,
                       DrawSelection selection = DrawSelection::Opaque, const LodView& lod = {}) const;
    // Draws the chunks of blended-material instances that intersect the frustum one by one, sorted back to front
    // by the distance from `eye` to each chunk's world-space bounding-box centre (glTF 3.9.4 BLEND), with the same
    // per-draw uniforms and cull state as drawInstances plus the emission uniform (location 5).
    void drawBlendedBackToFront(const Scene& scene, const glm::mat4& viewProjection, const glm::vec3& eye) const;
    bool hasBlended() const { return hasBlended_; }
    bool hasOpaqueEmissive() const { return hasOpaqueEmissive_; }
    int lightCount() const { return lightCount_; }
    // The last areaLightCount() of the lightCount() GPU lights are area lights (scene.h gpuLightOrder).
    int areaLightCount() const { return areaLightCount_; }
    // GL_TEXTURE_MAX_ANISOTROPY of the mipmapped linear material textures (texture_anisotropy); a no-op when
    // unchanged, so the renderer calls it every frame.
    void setTextureAnisotropy(float maxAnisotropy) const;
    // LEAN maps (Olano & Baker 2010) of every normal texture, for glint methods that filter normal maps
    // (GlintMethod::slopeCovariance): per texel the tangent-space slope m = -n.xy / n.z of the normal map and its
    // second moments, E[m] and E[m m^T] after mip filtering (the GL box filter averages moments exactly).
    // Made on the first call (RGBA16F + R16F with mips: 13 bytes per texel of the normal map); bound per draw at
    // UNIT_MATERIAL_LEAN_MOMENTS / _CROSS (mask bit 9) by the G-buffer pass's draws afterwards.
    void ensureLeanMaps(const Scene& scene) const;
    // Mesh-space chunks of a mesh (bounds for culling and for the shadow maps' scene bounds).
    const std::vector<MeshChunk>& meshChunks(uint32_t mesh) const { return meshes_[mesh].chunks; }
    size_t meshCount() const { return meshes_.size(); }
    // Unique per GpuScene built in this process: geometry never changes under one serial (baked data and the
    // shadow maps' cache key on it).
    uint64_t serial() const { return serial_; }

    struct DrawStats {
        size_t chunksTotal = 0, chunksDrawn = 0;
        size_t trianglesTotal = 0, trianglesDrawn = 0;
        size_t chunksCoarser = 0;          // chunks drawn at a simplified level
        size_t trianglesFullDetail = 0;    // what the drawn chunks have at level 0
    };
    // Counts of the last drawInstances call (for --stats).
    const DrawStats& lastDrawStats() const { return drawStats_; }

private:
    // Binds the instance's uniforms (locations 0-4; `forward` adds the emission at 5 and the emissive texture),
    // textures and cull / front-face state.
    // transformOnly: the face culling and the model matrix, no material (depth-only programs without a fragment
    // stage's work have no other uniforms).
    void bindInstance(const Scene& scene, const Instance& instance, bool forward, bool normalMatrix,
                      bool transformOnly = false) const;
    struct MeshBuffers {
        gl::VertexArray vao;
        gl::Buffer vertices, indices;
        GLsizei indexCount = 0;
        std::vector<MeshChunk> chunks;
    };
    std::vector<MeshBuffers> meshes_;
    std::vector<gl::Texture> textures_;
    mutable std::vector<gl::Texture> leanMoments_, leanCross_;   // per texture; empty ones for non-normal maps
    mutable bool leanMapsMade_ = false;
    std::vector<bool> anisotropic_;            // per texture: mipmapped and linear (anisotropy applies)
    mutable float textureAnisotropy_ = 16.0f;  // GL texture state, set through a const scene
    gl::Buffer materials_, lights_;
    int lightCount_ = 0, areaLightCount_ = 0;
    bool hasBlended_ = false, hasOpaqueEmissive_ = false;
    uint64_t serial_ = 0;
    mutable DrawStats drawStats_;
    mutable std::vector<GLsizei> drawCounts_;       // per-draw scratch for glMultiDrawElements
    mutable std::vector<const void*> drawOffsets_;
};

}  // namespace glimmer
