// Compute shader for tests/kemppinen2025_test.cpp: draws importance samples of the kemppinen2025 NDF at one
// surface point (GlintSurface from uniforms) and writes (h.xyz, pdf) and the prior-space point per invocation.
// The method's parameters come in the generated block (P_<NAME>), as in the lighting pass.
#include "common/frame.glsl"
#include "common/brdf.glsl"
#include "common/footprint.glsl"
#include "common/glint_surface.glsl"
#include "glints/kemppinen2025/kemppinen2025.glsl"
#include "glints/kemppinen2025/kemppinen2025_sampling.glsl"

layout(local_size_x = 64) in;

layout(location = 0) uniform vec2 u_uv;
layout(location = 1) uniform vec4 u_duv;       // duv/dx, duv/dy
layout(location = 2) uniform float u_alpha;
layout(location = 3) uniform int u_ndf;
layout(location = 4) uniform uint u_sampleCount;
layout(location = 5) uniform uint u_seedOffset;

layout(std430, binding = 8) writeonly buffer SampleBlock { vec4 o_samples[]; };   // h.xyz, pdf
layout(std430, binding = 9) writeonly buffer PriorBlock { vec2 o_priors[]; };

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= u_sampleCount) return;
    GlintSurface s = makeGlintSurface(u_uv, u_duv.xy, u_duv.zw, u_alpha, u_ndf, 1.0, ivec2(0), mat3(1.0));
    GlintPixel px = glintSetup(s);
    uint rng = kemppinenSeed(index + u_seedOffset);
    float pdf;
    vec2 prior;
    vec3 h = kemppinenSampleHalfVector(px, u_ndf, rng, pdf, prior);
    o_samples[index] = vec4(h, pdf);
    o_priors[index] = prior;
}
