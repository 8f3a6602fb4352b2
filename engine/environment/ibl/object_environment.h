// Sec. 3 of "Real-time Rendering of Glossy Materials with Regular Sampling" (CGI 2014): one environment map per
// glossy object, rendered from the scene at the object's centroid (the object itself left out) into a cube map, and
// a MIP pyramid built with the chosen filter (box 2x2, Gaussian 4x4 / 6x6; environment/ibl/cube_pyramid.h). A map is
// re-rendered only when something it depends on changed: the object's transform (its centroid), or any other
// instance, material or light of the scene.
// Used by the regular and fis IBL modes with ibl.object_maps = 1 (engine/environment/ibl/kurt_ibl_resources.cpp).
#pragma once
#include <glm/glm.hpp>

#include <filesystem>
#include <memory>
#include <vector>

#include "gl/handles.h"
#include "environment/ibl/cube_pyramid.h"
#include "environment/ibl/scene_capture.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace glimmer::ibl {

// World-space centroid of an instance: the mean of its transformed vertex positions.
glm::vec3 instanceCentroid(const Scene& scene, const Instance& instance);

// The camera that renders cube face `face` (GL order +X, -X, +Y, -Y, +Z, -Z) from `centre` so that the image's rows,
// read back bottom-up, are the face's rows in memory order (GL 4.5 spec, Table 8.19).
Camera cubeFaceCamera(glm::vec3 centre, int face);

class ObjectEnvironmentMaps {
public:
    ObjectEnvironmentMaps(std::filesystem::path shaderRoot, int faceSize, PyramidFilter filter);
    // Maps for the instances in `glossyInstances` (indices into scene.instances). Re-renders (through `capture`)
    // the maps whose inputs changed; returns how many were re-rendered.
    int update(const Scene& scene, const std::vector<uint32_t>& glossyInstances, SceneCapture& capture);
    GLuint cube(size_t i) const { return maps_[i].cube.id(); }
    glm::vec3 centroid(size_t i) const { return maps_[i].centroid; }
    int faceSize() const { return faceSize_; }
    // Level-0 face of map i read back (RGBA floats, memory row order).
    std::vector<float> readFace(size_t i, int face) const;

private:
    struct Map {
        uint32_t instance = 0;
        glm::vec3 centroid{0.0f};
        std::vector<float> key;   // everything the map was rendered from
        gl::Texture cube;
    };
    std::filesystem::path shaderRoot_;
    int faceSize_;
    PyramidFilter filter_;
    CubePyramidBuilder pyramid_;
    std::vector<Map> maps_;
};

}  // namespace glimmer::ibl
