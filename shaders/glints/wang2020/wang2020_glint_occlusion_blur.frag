// Wang, Deng & Holzschuch 2020, Sec. 4.4 "Gaussian Blurring", first step: the directional occlusion (0/1 visibility
// along the mirror direction, alpha of the environment-glint target) blurred by a Gaussian of 2 u_radius + 1 taps
// (paper: 9) into the weight delta that approximates soft shadows from the environment map; then the environment
// glints are multiplied by delta and the light glints added (the result the glint blur, glint_blur.frag, spreads).
// Separable, two draws: u_pass 0 sums along x into (sum w m v, sum w m), u_pass 1 along y and divides.
// Weights u_weights[|k|]: binomial coefficients C(2r, r + k) / 4^r, the discrete Gaussian of that width (sigma =
// sqrt(r / 2) pixels), computed once per frame on the CPU (engine/glints/wang2020/wang2020_post_pass.cpp).
// Deviation: only glinty pixels (mask m) contribute and the weights are renormalised over them, so visibility does
// not bleed in from the background or from other materials, which have none; the paper does not say how it
// treats them. Taps outside the image are skipped the same way.
layout(binding = 0) uniform sampler2D t_glintEnvironment;  // rgb: environment glints, a: visibility (0 or 1)
layout(binding = 1) uniform sampler2D t_glintLights;       // rgb: light glints, a: 1 on glinty pixels
layout(binding = 2) uniform sampler2D t_occlusionSums;     // pass 1: the output of pass 0

layout(location = 0) uniform int u_pass;
layout(location = 1) uniform int u_radius;
layout(location = 2) uniform float u_weights[16];

layout(location = 0) out vec4 o_value;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(t_glintEnvironment, 0);
    ivec2 axis = u_pass == 0 ? ivec2(1, 0) : ivec2(0, 1);
    vec2 sums = vec2(0.0);   // (sum of w m visibility, sum of w m)
    for (int k = -u_radius; k <= u_radius; ++k) {
        ivec2 q = pixel + k * axis;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        float w = u_weights[abs(k)];
        if (u_pass == 0) {
            float mask = texelFetch(t_glintLights, q, 0).a;
            sums += w * mask * vec2(texelFetch(t_glintEnvironment, q, 0).a, 1.0);
        } else {
            sums += w * texelFetch(t_occlusionSums, q, 0).rg;
        }
    }
    if (u_pass == 0) {
        o_value = vec4(sums, 0.0, 0.0);
        return;
    }
    float delta = sums.y > 0.0 ? sums.x / sums.y : 1.0;
    vec3 glint = texelFetch(t_glintEnvironment, pixel, 0).rgb * delta + texelFetch(t_glintLights, pixel, 0).rgb;
    o_value = vec4(glint, delta);
}
