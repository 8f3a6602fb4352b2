#include "render/gpu_scene.h"

#include <atomic>
#include "common/bindings.glsl"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "render/shader_interface.h"

namespace glimmer {
namespace {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec4 tangent;
    glm::vec2 uv;
    glm::vec4 color;   // COLOR_0, white when absent
};

GLint glWrap(TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge: return GL_CLAMP_TO_EDGE;
        case TextureWrap::MirroredRepeat: return GL_MIRRORED_REPEAT;
        default: return GL_REPEAT;
    }
}

bool isEmissive(const Material& m) { return m.emissive.x > 0.0f || m.emissive.y > 0.0f || m.emissive.z > 0.0f; }

bool filtersAnisotropically(const TextureData& data) { return data.sampler.mipmaps && !data.sampler.nearestMag; }

gl::Texture uploadTexture(const TextureData& data) {
    int levels = 1 + int(std::floor(std::log2(float(std::max(data.width, data.height)))));
    gl::Texture texture = gl::createTexture2D(data.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, data.width, data.height, levels);
    glTextureSubImage2D(texture.id(), 0, 0, 0, data.width, data.height, GL_RGBA, GL_UNSIGNED_BYTE, data.rgba.data());
    glGenerateTextureMipmap(texture.id());
    // The glTF sampler (3.8.3): wrap modes per axis; without mipmaps the level 0 alone is read.
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, glWrap(data.sampler.wrapS));
    glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, glWrap(data.sampler.wrapT));
    glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, data.sampler.mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, data.sampler.nearestMag ? GL_NEAREST : GL_LINEAR);
    // Anisotropic filtering for mipmapped linear textures only: it has no meaning without mip levels, and llvmpipe
    // (Mesa 22.3.6, LLVM 15) crashed inside LLVM compiling the G-buffer shader for a NEAREST texture with 16x
    // anisotropy (tests/data/texture_transform.gltf, ScenesGltf.TextureTransformChangesTheSampledTexels).
    if (GLAD_GL_EXT_texture_filter_anisotropic && filtersAnisotropically(data))
        glTextureParameterf(texture.id(), GL_TEXTURE_MAX_ANISOTROPY_EXT, 16.0f);
    return texture;
}

// The LEAN maps of one normal texture (GpuScene::ensureLeanMaps): the slope of each texel's normal, decoded as the
// G-buffer decodes it (rgb * 2 - 1, normalized; n.z clamped to 0.05 so that a slope stays below 20), and its
// products, with the normal texture's size, sampler and full mip chain.
void uploadLeanMaps(const TextureData& data, gl::Texture& moments, gl::Texture& cross) {
    const size_t texels = size_t(data.width) * data.height;
    std::vector<float> m4(texels * 4), mxy(texels);
    for (size_t i = 0; i < texels; ++i) {
        glm::vec3 n = glm::vec3(data.rgba[4 * i], data.rgba[4 * i + 1], data.rgba[4 * i + 2]) * (2.0f / 255.0f) - 1.0f;
        float length = glm::length(n);
        n = length > 1e-6f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
        float z = std::max(n.z, 0.05f);
        float sx = -n.x / z, sy = -n.y / z;
        m4[4 * i] = sx;
        m4[4 * i + 1] = sy;
        m4[4 * i + 2] = sx * sx;
        m4[4 * i + 3] = sy * sy;
        mxy[i] = sx * sy;
    }
    int levels = 1 + int(std::floor(std::log2(float(std::max(data.width, data.height)))));
    moments = gl::createTexture2D(GL_RGBA16F, data.width, data.height, levels);
    cross = gl::createTexture2D(GL_R16F, data.width, data.height, levels);
    glTextureSubImage2D(moments.id(), 0, 0, 0, data.width, data.height, GL_RGBA, GL_FLOAT, m4.data());
    glTextureSubImage2D(cross.id(), 0, 0, 0, data.width, data.height, GL_RED, GL_FLOAT, mxy.data());
    for (const gl::Texture* t : {&moments, &cross}) {
        glGenerateTextureMipmap(t->id());
        glTextureParameteri(t->id(), GL_TEXTURE_WRAP_S, glWrap(data.sampler.wrapS));
        glTextureParameteri(t->id(), GL_TEXTURE_WRAP_T, glWrap(data.sampler.wrapT));
        glTextureParameteri(t->id(), GL_TEXTURE_MIN_FILTER, data.sampler.mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
        glTextureParameteri(t->id(), GL_TEXTURE_MAG_FILTER, data.sampler.nearestMag ? GL_NEAREST : GL_LINEAR);
        if (GLAD_GL_EXT_texture_filter_anisotropic && filtersAnisotropically(data))
            glTextureParameterf(t->id(), GL_TEXTURE_MAX_ANISOTROPY_EXT, 16.0f);
    }
}

}  // namespace

void GpuScene::ensureLeanMaps(const Scene& scene) const {
    if (leanMapsMade_) return;
    leanMapsMade_ = true;
    leanMoments_.resize(textures_.size());
    leanCross_.resize(textures_.size());
    for (const Material& m : scene.materials) {
        int index = m.normalTexture;
        if (index < 0 || index >= int(scene.textures.size()) || index >= int(textures_.size()) || leanMoments_[index])
            continue;
        uploadLeanMaps(scene.textures[size_t(index)], leanMoments_[size_t(index)], leanCross_[size_t(index)]);
    }
}

GpuScene::GpuScene(const Scene& scene) {
    static std::atomic<uint64_t> nextSerial{1};
    serial_ = nextSerial++;
    // A mesh no instance draws (a scene file's generated mesh left unused) is neither chunked nor uploaded: every
    // draw goes through the instances.
    std::vector<bool> used(scene.meshes.size(), false);
    for (const Instance& instance : scene.instances)
        if (instance.mesh < used.size()) used[instance.mesh] = true;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const MeshData& mesh = scene.meshes[m];
        if (!used[m]) {
            meshes_.emplace_back();
            continue;
        }
        std::vector<Vertex> vertices(mesh.positions.size());
        for (size_t i = 0; i < vertices.size(); ++i) {
            vertices[i].position = mesh.positions[i];
            vertices[i].normal = i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0, 1, 0);
            vertices[i].tangent = i < mesh.tangents.size() ? mesh.tangents[i] : glm::vec4(1, 0, 0, 1);
            vertices[i].uv = i < mesh.uvs.size() ? mesh.uvs[i] : glm::vec2(0.0f);
            vertices[i].color = i < mesh.colors.size() ? mesh.colors[i] : glm::vec4(1.0f);
        }
        MeshBuffers buffers;
        ChunkedIndices chunked = buildMeshChunks(mesh.indices, mesh.positions);
        addChunkLods(chunked, mesh.positions);
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
            {2, 4, offsetof(Vertex, tangent)}, {3, 2, offsetof(Vertex, uv)}, {4, 4, offsetof(Vertex, color)}};
        for (const auto& a : attributes) {
            glEnableVertexArrayAttrib(vao, a.location);
            glVertexArrayAttribFormat(vao, a.location, a.size, GL_FLOAT, GL_FALSE, a.offset);
            glVertexArrayAttribBinding(vao, a.location, 0);
        }
        buffers.vao = gl::VertexArray(vao);
        meshes_.push_back(std::move(buffers));
    }
    for (const TextureData& texture : scene.textures) {
        textures_.push_back(uploadTexture(texture));
        anisotropic_.push_back(filtersAnisotropically(texture));
    }
    for (const Instance& instance : scene.instances) {
        const Material& m = scene.materials[instance.material];
        hasBlended_ = hasBlended_ || m.blend;
        hasOpaqueEmissive_ = hasOpaqueEmissive_ || (!m.blend && isEmissive(m));
    }
    updateMaterialsAndLights(scene);
}

GpuLight gpuLight(const Light& l) {
    // KHR_lights_punctual's spot falloff as scale and offset of cos(angle) (scene/light_falloff.cpp).
    float scale = 1.0f / std::max(0.001f, std::cos(l.innerConeAngle) - std::cos(l.outerConeAngle));
    GpuLight g{{l.vector, float(int(l.type))}, {l.color, l.intensity}, {l.spotDirection, scale},
               {-std::cos(l.outerConeAngle) * scale, l.range, 0.0f, l.intensity}, {0.0f, 0.0f, 0.0f, 0.0f},
               {0.0f, 0.0f, 0.0f, 0.0f}};
    constexpr float kPi = 3.14159265f;
    if (l.type == LightType::Directional) {
        // Solid angle of the sun's disk: 2 pi (1 - cos(diameter / 2)) = 4 pi sin^2(diameter / 4) (1 - cos loses its
        // digits in float at the sun's 0.53 degrees).
        float s = std::sin(0.25f * l.angularDiameter);
        g.spotOffsetRange.z = 4.0f * kPi * s * s;
    } else if (!l.isArea()) {
        g.spotOffsetRange.z = l.radius;
    } else {
        g.colorIntensity.w = l.radianceScale();
        g.spotOffsetRange.z = std::sqrt(std::max(l.area(), 0.0f) / (l.type == LightType::Sphere ? 4.0f * kPi : kPi));
        glm::vec3 normal = glm::normalize(l.spotDirection);
        glm::vec3 right = glm::normalize(l.right - normal * glm::dot(normal, l.right));
        glm::vec3 up = glm::cross(normal, right);   // cross(right, up) = normal: the front
        if (l.type == LightType::Rect) {
            g.areaU = {right * (0.5f * l.width), l.twoSided ? 1.0f : 0.0f};
            g.areaV = {up * (0.5f * l.height), 0.0f};
        } else if (l.type == LightType::Disk) {
            g.areaU = {right * l.radius, l.twoSided ? 1.0f : 0.0f};
            g.areaV = {up * l.radius, l.radius};
        } else {
            g.areaV = {0.0f, 0.0f, 0.0f, l.radius};
        }
    }
    return g;
}

void GpuScene::updateMaterialsAndLights(const Scene& scene) {
    std::vector<GpuMaterial> materials;
    for (const Material& m : scene.materials)
        materials.push_back({m.baseColor, {m.alpha, m.metallic, float(int(m.ndf)), m.glinty ? 1.0f : 0.0f},
                             {m.shadingDensityScale(), m.alphaCutoff, m.clearcoat, m.clearcoatRoughness}});
    if (materials.empty()) materials.push_back({});
    materials_ = gl::createBuffer(GLsizeiptr(materials.size() * sizeof(GpuMaterial)), materials.data(), 0);
    std::vector<GpuLight> lights;
    areaLightCount_ = 0;
    for (size_t index : gpuLightOrder(scene.lights)) {
        const Light& l = scene.lights[index];
        lights.push_back(gpuLight(l));
        areaLightCount_ += l.isArea() ? 1 : 0;
    }
    lightCount_ = int(lights.size());
    if (lights.empty()) lights.push_back({});
    lights_ = gl::createBuffer(GLsizeiptr(lights.size() * sizeof(GpuLight)), lights.data(), 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightBinding, lights_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaterialBinding, materials_.id());
}

void GpuScene::setTextureAnisotropy(float maxAnisotropy) const {
    if (maxAnisotropy == textureAnisotropy_ || !GLAD_GL_EXT_texture_filter_anisotropic) return;
    textureAnisotropy_ = maxAnisotropy;
    for (size_t i = 0; i < textures_.size(); ++i)
        if (anisotropic_[i]) glTextureParameterf(textures_[i].id(), GL_TEXTURE_MAX_ANISOTROPY_EXT, maxAnisotropy);
}

void GpuScene::bindInstance(const Scene& scene, const Instance& instance, bool forward, bool normalMatrix,
                            bool transformOnly) const {
    const Material& material = scene.materials[instance.material];
    // A transform with negative determinant mirrors the mesh, which turns counter-clockwise front faces clockwise
    // on screen (glTF 3.5.2 instantiation). The front face is set for two-sided materials too, so that
    // gl_FrontFacing (which flips their normals) stays right on mirrored nodes.
    glFrontFace(glm::determinant(glm::mat3(instance.transform)) < 0.0f ? GL_CW : GL_CCW);
    if (material.doubleSided) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
    }
    glUniformMatrix4fv(0, 1, GL_FALSE, glm::value_ptr(instance.transform));
    if (transformOnly) return;
    if (normalMatrix) {   // depth-only programs (shadow maps) have no normals
        glm::mat3 normals = glm::inverseTranspose(glm::mat3(instance.transform));
        glUniformMatrix3fv(1, 1, GL_FALSE, glm::value_ptr(normals));
    }
    glUniform1i(2, int(instance.material));
    const int slots[] = {material.baseColorTexture, material.metallicRoughnessTexture, material.normalTexture,
                         material.occlusionTexture, material.glintMaskTexture, material.emissiveTexture};
    int mask = 0;
    static_assert(UNIT_MATERIAL_BASE_COLOR == 0 && UNIT_MATERIAL_GLINT_MASK == 4 && UNIT_MATERIAL_EMISSIVE == 5,
                  "slots[] order = units");
    const int lastUnit = forward ? UNIT_MATERIAL_EMISSIVE : UNIT_MATERIAL_GLINT_MASK;
    for (int unit = UNIT_MATERIAL_BASE_COLOR; unit <= lastUnit; ++unit) {
        int index = slots[unit];
        if (index >= 0 && index < int(textures_.size())) {
            glBindTextureUnit(unit, textures_[index].id());
            mask |= 1 << unit;
        }
    }
    if (normalMatrix) {
        // KHR_materials_clearcoat's textures: units 6-8 in the G-buffer pass, 12-14 in the forward passes (6-7
        // hold the environment there). Mask bits 6-8 in both.
        const int coatSlots[] = {material.clearcoatTexture, material.clearcoatRoughnessTexture,
                                 material.clearcoatNormalTexture};
        static_assert(UNIT_MATERIAL_CLEARCOAT_NORMAL - UNIT_MATERIAL_CLEARCOAT == 2 &&
                      UNIT_FORWARD_CLEARCOAT_NORMAL - UNIT_FORWARD_CLEARCOAT == 2, "coatSlots[] order = units");
        const int firstUnit = forward ? UNIT_FORWARD_CLEARCOAT : UNIT_MATERIAL_CLEARCOAT;
        for (int k = 0; k < 3; ++k) {
            int index = coatSlots[k];
            if (index >= 0 && index < int(textures_.size())) {
                glBindTextureUnit(GLuint(firstUnit + k), textures_[index].id());
                mask |= 1 << (UNIT_MATERIAL_CLEARCOAT + k);
            }
        }
    }
    // LEAN maps of the normal texture (G-buffer pass, after ensureLeanMaps): mask bit 9.
    if (normalMatrix && !forward && material.normalTexture >= 0 && material.normalTexture < int(leanMoments_.size()) &&
        leanMoments_[size_t(material.normalTexture)]) {
        glBindTextureUnit(UNIT_MATERIAL_LEAN_MOMENTS, leanMoments_[size_t(material.normalTexture)].id());
        glBindTextureUnit(UNIT_MATERIAL_LEAN_CROSS, leanCross_[size_t(material.normalTexture)].id());
        mask |= 1 << 9;
    }
    glUniform1i(3, mask);
    glUniformMatrix3fv(4, 1, GL_FALSE, glm::value_ptr(material.uvTransform));
    if (forward) glUniform3fv(5, 1, glm::value_ptr(material.emissive));
}

LodView lodViewFor(const Camera& camera, int heightPixels, float maxPixelError) {
    LodView lod;
    lod.eye = camera.position;
    if (maxPixelError > 0.0f && heightPixels > 0)
        lod.errorPerDistance = maxPixelError * 2.0f * std::tan(0.5f * glm::radians(camera.verticalFovDegrees)) /
                               float(heightPixels);
    return lod;
}

void GpuScene::drawInstances(const Scene& scene, const glm::mat4& viewProjection, DrawSelection selection,
                             const LodView& lod) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightBinding, lights_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaterialBinding, materials_.id());
    DrawStats stats;   // kept for --stats from the G-buffer's draw only
    for (const Instance& instance : scene.instances) {
        const Material& material = scene.materials[instance.material];
        if (material.blend) continue;   // drawBlendedBackToFront
        if (selection == DrawSelection::OpaqueEmissive && !isEmissive(material)) continue;
        if (selection == DrawSelection::DepthOnlyUnmasked && material.alphaCutoff >= 0.0f) continue;
        if (selection == DrawSelection::DepthOnlyMasked && material.alphaCutoff < 0.0f) continue;
        const MeshBuffers& mesh = meshes_[instance.mesh];
        // Visible chunks; consecutive ones merge into one range (they are adjacent in the index buffer).
        const glm::mat4 clipFromMesh = viewProjection * instance.transform;
        // Mesh-space errors scale by the instance's largest axis scale into world space.
        const glm::mat3 linear(instance.transform);
        const float maxScale = std::sqrt(std::max({glm::dot(linear[0], linear[0]), glm::dot(linear[1], linear[1]),
                                                   glm::dot(linear[2], linear[2])}));
        drawCounts_.clear();
        drawOffsets_.clear();
        uint32_t rangeEnd = ~0u;
        for (const MeshChunk& chunk : mesh.chunks) {
            stats.chunksTotal += 1;
            stats.trianglesTotal += chunk.indexCount / 3;
            if (boxOutsideFrustum(clipFromMesh, chunk.boundsMin, chunk.boundsMax)) continue;
            ChunkLod range{chunk.firstIndex, chunk.indexCount, 0.0f};
            if (lod.errorPerDistance > 0.0f && chunk.coarserCount > 0 && maxScale > 0.0f) {
                const glm::vec3 centre(instance.transform * glm::vec4(0.5f * (chunk.boundsMin + chunk.boundsMax), 1.0f));
                const float radius = 0.5f * glm::length(chunk.boundsMax - chunk.boundsMin) * maxScale;
                const float distance = std::max(glm::length(centre - lod.eye) - radius, 0.0f);
                int level = 0;
                range = selectChunkLod(chunk, distance * lod.errorPerDistance / maxScale, level);
                stats.chunksCoarser += level > 0;
            }
            stats.chunksDrawn += 1;
            stats.trianglesDrawn += range.indexCount / 3;
            stats.trianglesFullDetail += chunk.indexCount / 3;
            if (range.firstIndex == rangeEnd) {
                drawCounts_.back() += GLsizei(range.indexCount);
            } else {
                drawCounts_.push_back(GLsizei(range.indexCount));
                drawOffsets_.push_back(reinterpret_cast<const void*>(size_t(range.firstIndex) * sizeof(uint32_t)));
            }
            rangeEnd = range.firstIndex + range.indexCount;
        }
        if (drawCounts_.empty()) continue;
        bindInstance(scene, instance, selection == DrawSelection::OpaqueEmissive,
                     selection == DrawSelection::Opaque || selection == DrawSelection::OpaqueEmissive,
                     selection == DrawSelection::DepthOnlyUnmasked);
        glBindVertexArray(mesh.vao.id());
        glMultiDrawElements(GL_TRIANGLES, drawCounts_.data(), GL_UNSIGNED_INT, drawOffsets_.data(),
                            GLsizei(drawCounts_.size()));
    }
    if (selection == DrawSelection::Opaque) drawStats_ = stats;
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
}

void GpuScene::drawBlendedBackToFront(const Scene& scene, const glm::mat4& viewProjection, const glm::vec3& eye) const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLightBinding, lights_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kMaterialBinding, materials_.id());
    struct Draw { float distance2; uint32_t instance; const MeshChunk* chunk; };
    std::vector<Draw> draws;
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        if (!scene.materials[instance.material].blend) continue;
        const glm::mat4 clipFromMesh = viewProjection * instance.transform;
        for (const MeshChunk& chunk : meshes_[instance.mesh].chunks) {
            if (boxOutsideFrustum(clipFromMesh, chunk.boundsMin, chunk.boundsMax)) continue;
            glm::vec3 centre = glm::vec3(instance.transform * glm::vec4(0.5f * (chunk.boundsMin + chunk.boundsMax), 1.0f));
            glm::vec3 d = centre - eye;
            draws.push_back({glm::dot(d, d), i, &chunk});
        }
    }
    // Farthest first; ties keep the file's order (stable), so coplanar layers draw deterministically.
    std::stable_sort(draws.begin(), draws.end(), [](const Draw& a, const Draw& b) { return a.distance2 > b.distance2; });
    uint32_t bound = ~0u;
    for (const Draw& draw : draws) {
        const Instance& instance = scene.instances[draw.instance];
        if (draw.instance != bound) {
            bindInstance(scene, instance, true, true);
            glBindVertexArray(meshes_[instance.mesh].vao.id());
            bound = draw.instance;
        }
        glDrawElements(GL_TRIANGLES, GLsizei(draw.chunk->indexCount), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(size_t(draw.chunk->firstIndex) * sizeof(uint32_t)));
    }
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
}

}  // namespace glimmer
