#include "environment/ibl/object_environment.h"

#include <cstring>

namespace glimmer::ibl {

glm::vec3 instanceCentroid(const Scene& scene, const Instance& instance) {
    const MeshData& mesh = scene.meshes.at(instance.mesh);
    glm::dvec3 sum(0.0);
    for (const glm::vec3& p : mesh.positions) sum += glm::dvec3(instance.transform * glm::vec4(p, 1.0f));
    return mesh.positions.empty() ? glm::vec3(instance.transform[3]) : glm::vec3(sum / double(mesh.positions.size()));
}

Camera cubeFaceCamera(glm::vec3 centre, int face) {
    static const glm::vec3 forward[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const glm::vec3 up[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    Camera camera;
    camera.name = "cube face " + std::to_string(face);
    camera.position = centre;
    camera.target = centre + forward[face];
    camera.up = up[face];
    camera.verticalFovDegrees = 90.0f;
    camera.nearPlane = 0.01f;
    return camera;
}

ObjectEnvironmentMaps::ObjectEnvironmentMaps(std::filesystem::path shaderRoot, int faceSize, PyramidFilter filter)
    : shaderRoot_(std::move(shaderRoot)), faceSize_(faceSize), filter_(filter), pyramid_(shaderRoot_) {}

// The inputs of one map: every instance's mesh, material and transform, materials and lights.
static std::vector<float> sceneKey(const Scene& scene, uint32_t self) {
    std::vector<float> key;
    key.push_back(float(self));
    for (const Instance& instance : scene.instances) {
        key.push_back(float(instance.mesh));
        key.push_back(float(instance.material));
        const float* m = &instance.transform[0][0];
        key.insert(key.end(), m, m + 16);
    }
    for (const Material& m : scene.materials) {
        key.insert(key.end(), {m.baseColor[0], m.baseColor[1], m.baseColor[2], m.alpha, m.metallic});
    }
    for (const Light& l : scene.lights) {
        key.insert(key.end(), {l.vector.x, l.vector.y, l.vector.z, l.color[0], l.color[1], l.color[2], l.intensity});
    }
    return key;
}

int ObjectEnvironmentMaps::update(const Scene& scene, const std::vector<uint32_t>& glossyInstances,
                                  SceneCapture& capture) {
    if (maps_.size() != glossyInstances.size()) maps_.resize(glossyInstances.size());
    int rendered = 0;
    for (size_t i = 0; i < glossyInstances.size(); ++i) {
        Map& map = maps_[i];
        std::vector<float> key = sceneKey(scene, glossyInstances[i]);
        if (map.cube && key == map.key && map.instance == glossyInstances[i]) continue;
        map.instance = glossyInstances[i];
        map.key = std::move(key);
        map.centroid = instanceCentroid(scene, scene.instances.at(map.instance));
        // The scene as seen from the centroid, without the object itself.
        Scene others = scene;
        others.instances.erase(others.instances.begin() + map.instance);
        std::vector<Camera> faces;
        for (int face = 0; face < 6; ++face) faces.push_back(cubeFaceCamera(map.centroid, face));
        std::vector<std::vector<float>> hdr = capture.renderHdr(others, faces, faceSize_);
        if (!map.cube) map.cube = createPyramidCube(faceSize_);
        for (int face = 0; face < 6; ++face)
            glTextureSubImage3D(map.cube.id(), 0, 0, 0, face, faceSize_, faceSize_, 1, GL_RGBA, GL_FLOAT,
                                hdr[size_t(face)].data());
        pyramid_.build(map.cube.id(), faceSize_, filter_);
        ++rendered;
    }
    return rendered;
}

std::vector<float> ObjectEnvironmentMaps::readFace(size_t i, int face) const {
    std::vector<float> all(size_t(faceSize_) * faceSize_ * 4 * 6);
    glGetTextureImage(maps_[i].cube.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(all.size() * sizeof(float)), all.data());
    size_t faceFloats = size_t(faceSize_) * faceSize_ * 4;
    return std::vector<float>(all.begin() + face * faceFloats, all.begin() + (face + 1) * faceFloats);
}

}  // namespace glimmer::ibl
