#include "scene/scene.h"

#include "core/error.h"

namespace glimmer {

size_t Scene::triangleCount() const {
    size_t count = 0;
    for (const Instance& instance : instances) count += meshes[instance.mesh].triangleCount();
    return count;
}

const Camera& Scene::camera(const std::string& name) const {
    if (cameras.empty()) throw Error("scene " + this->name + " has no camera");
    if (name.empty()) return cameras.front();
    for (const Camera& c : cameras)
        if (c.name == name) return c;
    std::string known;
    for (const Camera& c : cameras) known += (known.empty() ? "" : ", ") + c.name;
    throw UsageError("--camera: scene " + this->name + " has no camera '" + name + "' (has: " + known + ")");
}

void generateTangents(MeshData& mesh, BitangentConvention convention) {
    size_t n = mesh.positions.size();
    std::vector<glm::vec3> tan(n, glm::vec3(0.0f)), bitan(n, glm::vec3(0.0f));
    if (mesh.uvs.size() != n) mesh.uvs.assign(n, glm::vec2(0.0f));
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        glm::vec3 e1 = mesh.positions[b] - mesh.positions[a], e2 = mesh.positions[c] - mesh.positions[a];
        glm::vec2 d1 = mesh.uvs[b] - mesh.uvs[a], d2 = mesh.uvs[c] - mesh.uvs[a];
        float det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-20f) continue;
        float r = 1.0f / det;
        glm::vec3 t = (e1 * d2.y - e2 * d1.y) * r;
        glm::vec3 bt = (e2 * d1.x - e1 * d2.x) * r;
        for (uint32_t v : {a, b, c}) { tan[v] += t; bitan[v] += bt; }
    }
    mesh.tangents.resize(n);
    for (size_t v = 0; v < n; ++v) {
        glm::vec3 normal = mesh.normals[v];
        glm::vec3 t = tan[v] - normal * glm::dot(normal, tan[v]);
        if (glm::dot(t, t) < 1e-20f) {
            // No usable UV gradient: any vector orthogonal to the normal keeps the frame valid.
            glm::vec3 axis = std::abs(normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
            t = glm::cross(axis, normal);
        }
        t = glm::normalize(t);
        // bitan is dP/dv; ImageUp wants the bitangent along -dP/dv (glTF's image up).
        glm::vec3 wanted = convention == BitangentConvention::ImageUp ? -bitan[v] : bitan[v];
        float handedness = glm::dot(glm::cross(normal, t), wanted) < 0.0f ? -1.0f : 1.0f;
        mesh.tangents[v] = glm::vec4(t, handedness);
    }
}

}  // namespace glimmer
