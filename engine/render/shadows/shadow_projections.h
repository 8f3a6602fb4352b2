// Perspective shadow views of local lights: the six faces of a point light's cube (render/shadows/shadow_maps.h stores
// them as six layers of a 2D depth array, not a GL cube map, so each face is an ordinary perspective view with
// its own frustum for culling and the same 2D filtering code as the sun; a spot light is one such view).
// Depth is reversed-Z with an infinite far plane like the camera's: depth = near / view depth, 1 at the near plane.
#pragma once
#include <glm/glm.hpp>

namespace glimmer {

// World -> clip of a square perspective view from `eye` along `forward` (unit) with half-angle tangent `tanHalf`.
glm::mat4 perspectiveShadowView(const glm::vec3& eye, const glm::vec3& forward, float tanHalf, float nearPlane);

// Faces in the order the lighting shader picks them by the major axis of (point - light):
// +x, -x, +y, -y, +z, -z.
glm::vec3 cubeFaceDirection(int face);

// tan(half angle) of a face: a little over 45 degrees, so that a filter `guardTexels` wide around any point whose
// major axis selects the face still reads texels of that face (no seams between faces).
float cubeFaceTanHalf(int mapSize, float guardTexels);

// tan(half angle) of a spot light's view: the outer cone with a `guardTexels` band to spare at the map's edge.
float spotViewTanHalf(float outerConeAngle, int mapSize, float guardTexels);

// World size of one texel at view depth 1 m (multiply by the view depth).
inline float perspectiveTexelPerMetre(float tanHalf, int mapSize) { return 2.0f * tanHalf / float(mapSize); }

}  // namespace glimmer
