#include "render/ao/scene_rays.h"

#include <embree3/rtcore.h>

#include <cstring>
#include <limits>

#include "core/error.h"

namespace glimmer::ao {

WorldTriangles worldTriangles(const Scene& scene) {
    WorldTriangles out;
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const Instance& instance : scene.instances) {
        const MeshData& mesh = scene.meshes.at(instance.mesh);
        const uint32_t base = uint32_t(out.positions.size());
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(instance.transform)));
        std::vector<glm::vec3> normals;
        for (size_t v = 0; v < mesh.positions.size(); ++v) {
            glm::vec3 p = glm::vec3(instance.transform * glm::vec4(mesh.positions[v], 1.0f));
            out.positions.push_back(p);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
            normals.push_back(v < mesh.normals.size() ? normalMatrix * mesh.normals[v] : glm::vec3(0.0f));
        }
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
            out.indices.insert(out.indices.end(), {base + a, base + b, base + c});
            glm::vec3 n = normals[a] + normals[b] + normals[c];
            if (glm::dot(n, n) < 1e-12f) {   // no usable vertex normals: the winding decides
                glm::vec3 pa = out.positions[base + a];
                n = glm::cross(out.positions[base + b] - pa, out.positions[base + c] - pa);
            }
            float len = glm::length(n);
            out.frontNormals.push_back(len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f));
        }
    }
    if (!out.positions.empty()) out.boundsMin = lo, out.boundsMax = hi;
    return out;
}

SceneRays::SceneRays(const WorldTriangles& triangles) : frontNormals_(triangles.frontNormals) {
    RTCDevice device = rtcNewDevice(nullptr);
    if (!device) throw Error("embree: cannot create a device (error " + std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    device_ = device;
    RTCScene scene = rtcNewScene(device);
    scene_ = scene;
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    if (triangles.triangleCount() > 0) {
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        // Embree may read 16 bytes at the last vertex: one spare vertex of padding.
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), triangles.positions.size() + 1));
        std::memcpy(vertices, triangles.positions.data(), triangles.positions.size() * sizeof(glm::vec3));
        auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangles.triangleCount()));
        std::memcpy(indices, triangles.indices.data(), triangles.indices.size() * sizeof(uint32_t));
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(scene, geometry);
        rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(scene);
    if (RTCError e = rtcGetDeviceError(device); e != RTC_ERROR_NONE)
        throw Error("embree: scene build failed (error " + std::to_string(int(e)) + ")");
}

SceneRays::~SceneRays() {
    if (scene_) rtcReleaseScene(static_cast<RTCScene>(scene_));
    if (device_) rtcReleaseDevice(static_cast<RTCDevice>(device_));
}

RayHit SceneRays::cast(glm::vec3 origin, glm::vec3 direction, float tNear, float tFar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = origin.x, rh.ray.org_y = origin.y, rh.ray.org_z = origin.z;
    rh.ray.dir_x = direction.x, rh.ray.dir_y = direction.y, rh.ray.dir_z = direction.z;
    rh.ray.tnear = tNear;
    rh.ray.tfar = tFar;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(static_cast<RTCScene>(scene_), &context, &rh);
    RayHit result;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return result;
    result.hit = true;
    result.distance = rh.ray.tfar;
    result.backFace = glm::dot(frontNormals_[rh.hit.primID], direction) > 0.0f;
    return result;
}

}  // namespace glimmer::ao
