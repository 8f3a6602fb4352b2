#include "environment/cube_texels.h"

#include <cmath>

namespace glimmer::envref {

glm::vec3 cubeTexelDirection(int face, int x, int y, int size) {
    float s = 2.0f * (float(x) + 0.5f) / float(size) - 1.0f;
    float t = 2.0f * (float(y) + 0.5f) / float(size) - 1.0f;
    glm::vec3 d;
    switch (face) {
        case 0: d = {1.0f, -t, -s}; break;
        case 1: d = {-1.0f, -t, s}; break;
        case 2: d = {s, 1.0f, t}; break;
        case 3: d = {s, -1.0f, -t}; break;
        case 4: d = {s, -t, 1.0f}; break;
        default: d = {-s, -t, -1.0f}; break;
    }
    return glm::normalize(d);
}

// Solid angle of the face rectangle [-1, x] x [-1, y] seen from the centre, up to a constant (integral of
// (1 + s^2 + t^2)^(-3/2)); differences give a texel's exact solid angle.
static double areaElement(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); }

double cubeTexelSolidAngle(int x, int y, int size) {
    double x0 = 2.0 * x / size - 1.0, x1 = 2.0 * (x + 1) / size - 1.0;
    double y0 = 2.0 * y / size - 1.0, y1 = 2.0 * (y + 1) / size - 1.0;
    return areaElement(x0, y0) - areaElement(x0, y1) - areaElement(x1, y0) + areaElement(x1, y1);
}

}  // namespace glimmer::envref
