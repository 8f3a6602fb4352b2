// Display upscale: the internal-resolution display image (tone-mapped, sRGB-encoded RGBA8) resampled to the
// window with a separable Catmull-Rom cubic (B = 0, C = 0.5 in Mitchell & Netravali 1988): interpolating, sharper
// than bilinear, 4 x 4 texels. Filtering happens on display-encoded values, as post-tone-mapping upscalers do; the
// negative lobes' overshoot is clamped to [0, 1]. engine/render/image/upscale.cpp holds the CPU reference of this filter.
layout(binding = 0) uniform sampler2D t_source;
layout(location = 0) uniform ivec2 u_sourceSize;
layout(location = 1) uniform vec2 u_sourceFromTarget;   // source size / target size
layout(location = 0) out vec4 o_color;

vec4 catmullRomWeights(float t) {
    float t2 = t * t, t3 = t2 * t;
    return 0.5 * vec4(-t + 2.0 * t2 - t3, 2.0 - 5.0 * t2 + 3.0 * t3, t + 4.0 * t2 - 3.0 * t3, -t2 + t3);
}

void main() {
    // Texel centres of the source sit at integer + 0.5: p is the position in texel-index units.
    vec2 p = gl_FragCoord.xy * u_sourceFromTarget - 0.5;
    vec2 base = floor(p);
    vec2 t = p - base;
    vec4 wx = catmullRomWeights(t.x), wy = catmullRomWeights(t.y);
    ivec2 i0 = ivec2(base) - 1;
    ivec2 last = u_sourceSize - 1;
    vec3 sum = vec3(0.0);
    for (int j = 0; j < 4; ++j) {
        int y = clamp(i0.y + j, 0, last.y);
        vec3 row = vec3(0.0);
        for (int i = 0; i < 4; ++i) row += wx[i] * texelFetch(t_source, ivec2(clamp(i0.x + i, 0, last.x), y), 0).rgb;
        sum += wy[j] * row;
    }
    o_color = vec4(clamp(sum, 0.0, 1.0), 1.0);
}
