// GL cube-map texel conventions shared by the environment precomputation (SH projection) and the CPU references.
#pragma once
#include <glm/glm.hpp>

#include <vector>

namespace glimmer::envref {

// GL cube-map conventions (OpenGL 4.5 spec, Table 8.19): face order +X, -X, +Y, -Y, +Z, -Z; (x, y) is the texel in
// memory order (row y = 0 first), as imageStore and glGetTextureImage see it.
glm::vec3 cubeTexelDirection(int face, int x, int y, int size);   // unit direction through the texel centre
double cubeTexelSolidAngle(int x, int y, int size);                // exact, sums to 4 pi over the 6 faces

// One cube-map level read back from the GPU: 6 faces of size x size RGBA floats, faces in GL order.
struct CubeImage {
    int size = 0;
    std::vector<float> rgba;    // 6 * size * size * 4
    glm::vec3 texel(int face, int x, int y) const {
        const float* p = &rgba[((size_t(face) * size + y) * size + x) * 4];
        return {p[0], p[1], p[2]};
    }
};

}  // namespace glimmer::envref
