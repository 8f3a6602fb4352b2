// Shadow maps: depth of the scene from one shadow view (render/shadows/shadow_map_pass.cpp). UVs only for alpha
// masks.
#include "common/frame.glsl"

layout(location = 0) in vec3 a_position;
layout(location = 3) in vec2 a_uv;

layout(location = 0) uniform mat4 u_model;
layout(location = 5) uniform mat4 u_shadowViewProjection;

out vec2 v_uv;

void main() {
    v_uv = a_uv;
    gl_Position = u_shadowViewProjection * (u_model * vec4(a_position, 1.0));
}
