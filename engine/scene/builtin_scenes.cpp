#include "scene/builtin_scenes.h"

#include <glm/gtc/constants.hpp>

#include "core/error.h"
#include "scene/atrium.h"

namespace glimmer {

const std::vector<std::string>& builtinSceneNames() {
    static const std::vector<std::string> names = {"plane90", "plane25", "heightmap90", "heightmap25", "sphere",
                                                    "atrium"};
    return names;
}

bool isBuiltinScene(const std::string& name) {
    for (const std::string& n : builtinSceneNames())
        if (n == name) return true;
    return false;
}

MeshData makeGroundPlane(float halfExtent, int cells, float uvOffset) {
    MeshData mesh;
    mesh.name = "ground";
    int n = cells + 1;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            float x = -halfExtent + 2.0f * halfExtent * i / cells;
            float z = -halfExtent + 2.0f * halfExtent * j / cells;
            mesh.positions.push_back({x, 0.0f, z});
            mesh.normals.push_back({0.0f, 1.0f, 0.0f});
            mesh.uvs.push_back({x + uvOffset, z + uvOffset});
            // dP/du = +x, dP/dv = +z, cross(n, t) = -z: handedness -1.
            mesh.tangents.push_back({1.0f, 0.0f, 0.0f, -1.0f});
        }
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
        }
    return mesh;
}

// A sum of oriented sine waves with wavelengths between 0.15 m and 0.6 m: high frequency relative to the view,
// so normals vary within a few pixels of plane25.
static constexpr struct Wave { float kx, kz, amplitude, phase; } kWaves[] = {
    {10.5f, 3.1f, 0.010f, 0.3f}, {-4.2f, 16.0f, 0.006f, 1.7f}, {27.0f, -11.0f, 0.003f, 2.9f},
    {-19.0f, -25.0f, 0.002f, 0.8f}, {33.0f, 30.0f, 0.0015f, 4.1f}};

float heightmapHeight(float x, float z) {
    float h = 0.0f;
    for (const Wave& w : kWaves) h += w.amplitude * std::sin(w.kx * x + w.kz * z + w.phase);
    return h;
}

static glm::vec2 heightmapGradient(float x, float z) {
    glm::vec2 g(0.0f);
    for (const Wave& w : kWaves) {
        float c = w.amplitude * std::cos(w.kx * x + w.kz * z + w.phase);
        g += glm::vec2(w.kx * c, w.kz * c);
    }
    return g;
}

MeshData makeHeightmapPlane(float halfExtent, int cells, float uvOffset) {
    MeshData mesh = makeGroundPlane(halfExtent, cells, uvOffset);
    mesh.name = "heightmap";
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        glm::vec3& p = mesh.positions[v];
        p.y = heightmapHeight(p.x, p.z);
        glm::vec2 g = heightmapGradient(p.x, p.z);
        glm::vec3 tangentU = glm::normalize(glm::vec3(1.0f, g.x, 0.0f));  // dP/du with u = x
        glm::vec3 tangentV = glm::vec3(0.0f, g.y, 1.0f);                  // dP/dv with v = z
        glm::vec3 normal = glm::normalize(glm::cross(tangentV, tangentU));
        mesh.normals[v] = normal;
        glm::vec3 t = glm::normalize(tangentU - normal * glm::dot(normal, tangentU));
        mesh.tangents[v] = glm::vec4(t, glm::dot(glm::cross(normal, t), tangentV) < 0.0f ? -1.0f : 1.0f);
    }
    return mesh;
}

MeshData makeUvSphere(float radius, int segments, int rings) {
    MeshData mesh;
    mesh.name = "sphere";
    const float pi = glm::pi<float>();
    for (int r = 0; r <= rings; ++r) {
        float theta = pi * r / rings;
        for (int s = 0; s <= segments; ++s) {
            float phi = 2.0f * pi * s / segments;
            glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
            mesh.positions.push_back(radius * n);
            mesh.normals.push_back(n);
            mesh.uvs.push_back({radius * phi, radius * theta});
            // dP/dphi = (-sin(phi), 0, -cos(phi)) * sin(theta) r; at the poles fall back to the same azimuth.
            glm::vec3 t(-std::sin(phi), 0.0f, -std::cos(phi));
            glm::vec3 dPdtheta(std::cos(theta) * std::cos(phi), -std::sin(theta), -std::cos(theta) * std::sin(phi));
            mesh.tangents.push_back({t, glm::dot(glm::cross(n, t), dPdtheta) < 0.0f ? -1.0f : 1.0f});
        }
    }
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            uint32_t a = r * (segments + 1) + s, b = a + 1, c = a + segments + 1, d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
        }
    return mesh;
}

static Material glintyMetal(const std::string& name) {
    Material m;
    m.name = name;
    m.baseColor = {0.95f, 0.93f, 0.88f, 1.0f};
    m.alpha = 0.3f;
    m.metallic = 1.0f;
    m.ndf = NdfType::Ggx;
    m.glinty = true;
    // The glint material every method maps from (README "Glint material"): 2e6 facets per m^2 (UVs are metres
    // here), each reflecting within 0.015 rad of h.
    m.glint.density = 2e6f;
    m.glint.angularSize = 0.015f;
    return m;
}

static Light directional(glm::vec3 towardLight, float intensity, glm::vec3 color = glm::vec3(1.0f)) {
    return {LightType::Directional, glm::normalize(towardLight), color, intensity};
}

static Scene planeScene(const std::string& name, bool heightmap, bool grazing) {
    Scene scene;
    scene.name = name;
    scene.skyColor = {0.05f, 0.06f, 0.08f};
    // The plane is large enough to fill a 25-degree view out to the horizon band; heightmaps are smaller
    // (tessellated) and their grazing camera sits lower so the displaced grid still fills the view.
    scene.meshes.push_back(heightmap ? makeHeightmapPlane(16.0f, 400, kPlaneUvOffset)
                                     : makeGroundPlane(kPlaneHalfExtent, 8, kPlaneUvOffset));
    scene.materials.push_back(glintyMetal(heightmap ? "heightmap" : "plane"));
    scene.instances.push_back({0, 0, glm::mat4(1.0f)});
    if (!grazing) {
        // Head-on: looking straight down from 2 m; the light sits near the view direction so the highlight shows.
        Camera top;
        top.name = "top";
        top.position = {0.0f, 2.0f, 0.0f};
        top.target = {0.0f, 0.0f, 0.0f};
        top.up = {0.0f, 0.0f, -1.0f};
        scene.cameras.push_back(top);
        scene.lights.push_back(directional({0.25f, 1.0f, 0.15f}, 1.0f));
    } else {
        // 25 degrees: the view axis meets the plane at 25 degrees; the light faces the camera, low over the plane,
        // so the specular lobe is seen along strongly anisotropic footprints.
        float height = heightmap ? 0.6f : 1.0f;
        float angle = glm::radians(25.0f);
        Camera grazingCamera;
        grazingCamera.name = "grazing";
        grazingCamera.position = {0.0f, height, heightmap ? 15.0f : 10.0f};
        grazingCamera.target = grazingCamera.position + glm::vec3(0.0f, -std::sin(angle), -std::cos(angle));
        scene.cameras.push_back(grazingCamera);
        scene.lights.push_back(directional({0.0f, 0.45f, -1.0f}, 1.0f));
    }
    return scene;
}

static Scene sphereScene() {
    Scene scene;
    scene.name = "sphere";
    scene.skyColor = {0.05f, 0.06f, 0.08f};
    scene.meshes.push_back(makeUvSphere(1.0f, 128, 64));
    scene.materials.push_back(glintyMetal("sphere"));
    scene.instances.push_back({0, 0, glm::mat4(1.0f)});
    Camera front;
    front.name = "front";
    front.position = {0.0f, 0.4f, 3.4f};
    front.target = {0.0f, 0.0f, 0.0f};
    scene.cameras.push_back(front);
    scene.lights.push_back(directional({-0.5f, 0.7f, 0.6f}, 2.0f));
    return scene;
}

Scene makeBuiltinScene(const std::string& name) {
    if (name == "plane90") return planeScene(name, false, false);
    if (name == "plane25") return planeScene(name, false, true);
    if (name == "heightmap90") return planeScene(name, true, false);
    if (name == "heightmap25") return planeScene(name, true, true);
    if (name == "sphere") return sphereScene();
    if (name == "atrium") return makeAtriumScene();
    throw UsageError("--scene: unknown scene '" + name + "'");
}

}  // namespace glimmer
