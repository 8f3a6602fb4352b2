// Test probe: runs a glint method's glintSetup + glintD on synthetic surfaces (UV, derivatives, half vector) and
// writes D, the footprint AOV and the extra AOV. Used by check-method (engine/checks/method_checks.cpp) and the
// tests (engine/reference/method_probe.cpp) to check the real shader code with controlled footprints.
#include "common/bindings.glsl"
layout(local_size_x = 64) in;
#include "common/constants.glsl"
// Methods may read the frame (kemppinen2025's triplanar mode); the probe binds an identity camera.
#include "common/frame.glsl"
#include "common/brdf.glsl"
#include "common/footprint.glsl"
#include "common/glint_surface.glsl"
#include GLINT_METHOD_FILE

struct ProbeInput {
    vec4 uvDuvdx;          // uv, duv/dx
    vec4 duvdyAlphaNdf;    // duv/dy, alpha, ndf
    vec4 halfDensity;      // h (shading frame), density scale
};
layout(std430, binding = BINDING_METHOD_LAST - 1) readonly buffer ProbeInputs { ProbeInput u_probeIn[]; };
layout(std430, binding = BINDING_METHOD_LAST) writeonly buffer ProbeOutputs { vec4 u_probeOut[]; };   // 3 per probe

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(u_probeIn.length())) return;
    ProbeInput probe = u_probeIn[i];
    GlintSurface s = makeGlintSurface(probe.uvDuvdx.xy, probe.uvDuvdx.zw, probe.duvdyAlphaNdf.xy,
                                      probe.duvdyAlphaNdf.z, int(probe.duvdyAlphaNdf.w + 0.5), probe.halfDensity.w,
                                      ivec2(int(i), 0), mat3(1.0));
    GlintPixel px = glintSetup(s);
    vec3 h = normalize(probe.halfDensity.xyz);
    vec3 wo = vec3(0.0, 0.0, 1.0);
    vec3 wi = reflect(-wo, h);
    float D = glintD(px, s, h, wi, wo);
    u_probeOut[3u * i] = vec4(D, D_smooth(h, s.alpha, s.ndf), 0.0, 0.0);
    u_probeOut[3u * i + 1u] = glintFootprintAOV(px, s);
    u_probeOut[3u * i + 2u] = glintExtraAOV(px, s);
}
