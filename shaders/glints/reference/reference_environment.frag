// Method `reference`, after the lighting pass: adds the environment glints the CPU computed per pixel
// (engine/reference/discrete_facets/environment_glints.h: the facets' reflection of the map minus the smooth
// lobe the IBL mode already gave the pixel), with the frame's blend weight (additive blending set by the pass).
layout(binding = 0) uniform sampler2DArray u_referenceD;
layout(location = 0) uniform int u_layer;
layout(location = 0) out vec4 o_color;

void main() {
    vec4 texel = texelFetch(u_referenceD, ivec3(ivec2(gl_FragCoord.xy), u_layer), 0);
    vec3 c = texel.a > 0.5 ? texel.rgb : vec3(0.0);
    bvec3 bad = bvec3(isnan(c.x) || isinf(c.x), isnan(c.y) || isinf(c.y), isnan(c.z) || isinf(c.z));
    o_color = vec4(any(bad) ? vec3(0.0) : c, 0.0);
}
