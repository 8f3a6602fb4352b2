#include "render/gpu_scene.h"
#include "common/bindings.glsl"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>

#include "render/shader_interface.h"

namespace glimmer {
namespace {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec4 tangent;
    glm::vec2 uv;
};

gl::Texture uploadTexture(const TextureData& data) {
    int levels = 1 + int(std::floor(std::log2(float(std::max(data.width, data.height)))));
    gl::Texture texture = gl::createTexture2D(data.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, data.width, data.height, levels);
    glTextureSubImage2D(texture.id(), 0, 0, 0, data.width, data.height, GL_RGBA, GL_UNSIGNED_BYTE, data.rgba.data());
    glGenerateTextureMipmap(texture.id());
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
    if (GLAD_GL_EXT_texture_filter_anisotropic) glTextureParameterf(texture.id(), GL_TEXTURE_MAX_ANISOTROPY_EXT, 16.0f);
    return texture;
}

}  // namespace

GpuScene::GpuScene(const Scene& scene) {
    for (const MeshData& mesh : scene.meshes) {
        std::vector<Vertex> vertices(mesh.positions.size());
        for (size_t i = 0; i < vertices.size(); ++i) {
            vertices[i].position = mesh.positions[i];
            vertices[i].normal = i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0, 1, 0);
            vertices[i].tangent = i < mesh.tangents.size() ? mesh.tangents[i] : glm::vec4(1, 0, 0, 1);
            vertices[i].uv = i < mesh.uvs.size() ? mesh.uvs[i] : glm::vec2(0.0f);
        }
        MeshBuffers buffers;
        ChunkedIndices chunked = buildMeshChunks(mesh.indices, mesh.positions);
        buffers.vertices = gl::createBuffer(GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(), 0);
        buffers.indices = gl::createBuffer(GLsizeiptr(std::max<size_t>(chunked.indices.size(), 1) * sizeof(uint32_t)),
                                           chunked.indices.empty() ? nullptr : chunked.indices.data(), 0);
        buffers.indexCount = GLsizei(chunked.indices.size());
        buffers.chunks = std::move(chunked.chunks);
        GLuint vao = 0;
        glCreateVertexArrays(1, &vao);
        glVertexArrayVertexBuffer(vao, 0, buffers.vertices.id(), 0, sizeof(Vertex));
        glVertexArrayElementBuffer(vao, buffers.indices.id());
        const struct { GLuint location; GLint size; GLuint offset; } attributes[] = {
            {0, 3, offsetof(Vertex, position)}, {1, 3, offsetof(Vertex, normal)},
            {2, 4, offsetof(Vertex, tangent)}, {3, 2, offsetof(Vertex, uv)}};
        for (const auto& a : attributes) {
            glEnableVertexArrayAttrib(vao, a.location);
            glVertexArrayAttribFormat(vao, a.location, a.size, GL_FLOAT, GL_FALSE, a.offset);
            glVertexArrayAttribBinding(vao, a.location, 0);
        }
        buffers.vao = gl::VertexArray(vao);
        meshes_.push_back(std::move(buffers));
    }
    for (const TextureData& texture : scene.textures) textures_.push_back(uploadTexture(texture));
    updateMaterialsAndLights(scene);
}

void GpuScene::updateMaterialsAndLights(const Scene& scene) {
    std::vector<GpuMaterial> materials;
    for (const Material& m : scene.materials)
        materials.push_back({m.baseColor, {m.alpha, m.metallic, float(int(m.ndf)), m.glinty ? 1.0f : 0.0f},
                             {m.glintDensityScale, m.alphaCutoff, 0.0f, 0.0f}});
    if (materials.empty()) materials.push_back({});
    materials_ = gl::createBuffer(GLsizeiptr(materials.size() * sizeof(GpuMaterial)), materials.data(), 0);
    std::vector<GpuLight> lights;
    for (const Light& l : scene.lights) {
        // KHR_lights_punctual's spot falloff as scale and offset of cos(angle) (scene/light_falloff.cpp).
        float scale = 1.0f / std::max(0.001f, std::cos(l.innerConeAngle) - std::cos(l.outerConeAngle));
        lights.push_back({{l.vector, float(int(l.type))}, {l.color, l.intensity}, {l.spotDirection, scale},
                          {-std::cos(l.outerConeAngle) * scale, l.range, 0.0f, 0.0f}});
    }
    lightCount_ = int(lights.size());
    if (lights.empty()) lights.push_back({});
    lights_ = gl::createBuffer(GLsizeiptr(lights.size() * sizeof(GpuLight)), lights.data(), 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightBinding, lights_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaterialBinding, materials_.id());
}

void GpuScene::drawInstances(const Scene& scene, const glm::mat4& viewProjection) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightBinding, lights_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaterialBinding, materials_.id());
    drawStats_ = {};
    for (const Instance& instance : scene.instances) {
        const MeshBuffers& mesh = meshes_[instance.mesh];
        // Visible chunks; consecutive ones merge into one range (they are adjacent in the index buffer).
        const glm::mat4 clipFromMesh = viewProjection * instance.transform;
        drawCounts_.clear();
        drawOffsets_.clear();
        uint32_t rangeEnd = ~0u;
        for (const MeshChunk& chunk : mesh.chunks) {
            drawStats_.chunksTotal += 1;
            drawStats_.trianglesTotal += chunk.indexCount / 3;
            if (boxOutsideFrustum(clipFromMesh, chunk.boundsMin, chunk.boundsMax)) continue;
            drawStats_.chunksDrawn += 1;
            drawStats_.trianglesDrawn += chunk.indexCount / 3;
            if (chunk.firstIndex == rangeEnd) {
                drawCounts_.back() += GLsizei(chunk.indexCount);
            } else {
                drawCounts_.push_back(GLsizei(chunk.indexCount));
                drawOffsets_.push_back(reinterpret_cast<const void*>(size_t(chunk.firstIndex) * sizeof(uint32_t)));
            }
            rangeEnd = chunk.firstIndex + chunk.indexCount;
        }
        if (drawCounts_.empty()) continue;
        const Material& material = scene.materials[instance.material];
        if (material.doubleSided) {
            glDisable(GL_CULL_FACE);
        } else {
            // A transform with negative determinant mirrors the mesh, which turns counter-clockwise front faces
            // clockwise on screen.
            glEnable(GL_CULL_FACE);
            glCullFace(GL_BACK);
            glFrontFace(glm::determinant(glm::mat3(instance.transform)) < 0.0f ? GL_CW : GL_CCW);
        }
        glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(instance.transform));
        glUniformMatrix4fv(0, 1, GL_FALSE, glm::value_ptr(instance.transform));
        glUniformMatrix3fv(1, 1, GL_FALSE, glm::value_ptr(normalMatrix));
        glUniform1i(2, int(instance.material));
        const int slots[] = {material.baseColorTexture, material.metallicRoughnessTexture, material.normalTexture,
                             material.occlusionTexture, material.glintMaskTexture};
        int mask = 0;
        static_assert(UNIT_MATERIAL_BASE_COLOR == 0 && UNIT_MATERIAL_GLINT_MASK == 4, "slots[] order = units");
        for (int unit = UNIT_MATERIAL_BASE_COLOR; unit <= UNIT_MATERIAL_GLINT_MASK; ++unit) {
            int index = slots[unit];
            if (index >= 0 && index < int(textures_.size())) {
                glBindTextureUnit(unit, textures_[index].id());
                mask |= 1 << unit;
            }
        }
        glUniform1i(3, mask);
        glUniformMatrix3fv(4, 1, GL_FALSE, glm::value_ptr(material.uvTransform));
        glBindVertexArray(mesh.vao.id());
        glMultiDrawElements(GL_TRIANGLES, drawCounts_.data(), GL_UNSIGNED_INT, drawOffsets_.data(),
                            GLsizei(drawCounts_.size()));
    }
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
}

}  // namespace glimmer
