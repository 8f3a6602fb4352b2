// Wang, Deng & Holzschuch 2020, Sec. 4.4 "Gaussian Blurring", second step: the occluded glints blurred by a
// Gaussian of 2 u_radius + 1 taps (paper: 3) "to avoid aliasing of glint shapes", then added to the HDR radiance
// (the renderer blends with GL_CONSTANT_ALPHA, GL_ONE: weight 1, or 1 / (k + 1) into a running mean).
// 2D kernel u_weights[|i|] u_weights[|j|] (binomial, see glint_occlusion_blur.frag), renormalised over the taps
// inside the image. The paper blurs "the computed glints" of the environment path; we blur the light glints
// (Sec. 5) with the same kernel.
layout(binding = 0) uniform sampler2D t_occludedGlint;     // rgb: occluded glints, a: delta

layout(location = 1) uniform int u_radius;
layout(location = 2) uniform float u_weights[16];

layout(location = 0) out vec4 o_color;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(t_occludedGlint, 0);
    vec3 sum = vec3(0.0);
    float weightSum = 0.0;
    for (int j = -u_radius; j <= u_radius; ++j)
        for (int i = -u_radius; i <= u_radius; ++i) {
            ivec2 q = pixel + ivec2(i, j);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            float w = u_weights[abs(i)] * u_weights[abs(j)];
            sum += w * texelFetch(t_occludedGlint, q, 0).rgb;
            weightSum += w;
        }
    o_color = vec4(sum / max(weightSum, 1e-30), 0.0);
}
