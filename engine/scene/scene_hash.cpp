#include "scene/scene_hash.h"

#include <cstddef>

#include "core/cache_file.h"

namespace glimmer {

namespace {
void addVec(cache::ContentHasher& h, const float* values, int count) { h.add(values, size_t(count) * sizeof(float)); }
}  // namespace

std::string sceneContentHash(const Scene& scene) {
    // A new field of Material or Light must be hashed below: this catches one that was added without it.
    static_assert(offsetof(Light, twoSided) == 20 * sizeof(float) + sizeof(LightType) &&
                      sizeof(Light) == offsetof(Light, twoSided) + alignof(float),
                  "hash the new Light field below");
    cache::ContentHasher h;
    h.add(uint64_t(scene.meshes.size()));
    for (const MeshData& m : scene.meshes) {
        h.addVector(m.positions).addVector(m.normals).addVector(m.tangents).addVector(m.uvs).addVector(m.colors);
        h.addVector(m.indices);
    }
    h.add(uint64_t(scene.textures.size()));
    for (const TextureData& t : scene.textures) {
        h.add(uint64_t(t.width)).add(uint64_t(t.height)).add(uint64_t(t.srgb)).addVector(t.rgba);
        h.add(uint64_t(t.sampler.wrapS)).add(uint64_t(t.sampler.wrapT)).add(uint64_t(t.sampler.mipmaps));
        h.add(uint64_t(t.sampler.nearestMag));
    }
    h.add(uint64_t(scene.materials.size()));
    for (const Material& m : scene.materials) {
        addVec(h, &m.baseColor[0], 4);
        h.add(m.alpha).add(m.metallic).add(uint64_t(m.ndf)).add(uint64_t(m.glinty));
        h.add(m.glint.density).add(m.glint.angularSize).add(m.glint.colorVariation).add(m.glint.anisotropy);
        addVec(h, &m.glint.color[0], 3);
        h.add(m.glintDensityScale).add(m.surfacePerUvArea).add(m.alphaCutoff).add(uint64_t(m.blend));
        addVec(h, &m.emissive[0], 3);
        for (int t : {m.emissiveTexture, m.baseColorTexture, m.metallicRoughnessTexture, m.normalTexture,
                      m.occlusionTexture, m.glintMaskTexture, m.clearcoatTexture, m.clearcoatRoughnessTexture,
                      m.clearcoatNormalTexture})
            h.add(uint64_t(int64_t(t)));
        h.add(uint64_t(m.doubleSided)).add(m.clearcoat).add(m.clearcoatRoughness);
        addVec(h, &m.uvTransform[0][0], 9);
    }
    h.add(uint64_t(scene.instances.size()));
    for (const Instance& i : scene.instances) {
        h.add(uint64_t(i.mesh)).add(uint64_t(i.material));
        addVec(h, &i.transform[0][0], 16);
    }
    h.add(uint64_t(scene.lights.size()));
    for (const Light& l : scene.lights) {
        h.add(uint64_t(l.type));
        addVec(h, &l.vector[0], 3);
        addVec(h, &l.color[0], 3);
        addVec(h, &l.spotDirection[0], 3);
        h.add(l.intensity).add(l.innerConeAngle).add(l.outerConeAngle).add(l.range);
        h.add(l.angularDiameter).add(l.radius).add(l.width).add(l.height).add(uint64_t(l.twoSided));
        addVec(h, &l.right[0], 3);
    }
    addVec(h, &scene.skyColor[0], 3);
    h.add(scene.environment);
    return h.digest();
}

}  // namespace glimmer
