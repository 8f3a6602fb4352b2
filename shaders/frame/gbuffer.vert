// G-buffer geometry pass: world-space frame and UV0 to the fragment stage.
#include "common/frame.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_tangent;
layout(location = 3) in vec2 a_uv;
layout(location = 4) in vec4 a_color;   // glTF COLOR_0 (white when the mesh has none)

layout(location = 0) uniform mat4 u_model;
layout(location = 1) uniform mat3 u_normalMatrix;

out vec3 v_normal;
out vec4 v_tangent;
out vec2 v_uv;
out vec4 v_color;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_normal = u_normalMatrix * a_normal;
    // A mirroring transform (negative determinant) reverses cross(n, t) relative to the transformed bitangent:
    // flip the handedness so w * cross(n, t) stays the image's bitangent (NegativeScaleTest).
    float mirror = determinant(mat3(u_model)) < 0.0 ? -1.0 : 1.0;
    v_tangent = vec4(mat3(u_model) * a_tangent.xyz, a_tangent.w * mirror);
    v_uv = a_uv;
    v_color = a_color;
    gl_Position = u_viewProjection * world;
}
