// Deferred lighting: one full-screen pass reading the G-buffer. Position is rebuilt from depth.
// Cook-Torrance (common/brdf.glsl) with D from the selected glint method on glinty materials, Lambert diffuse,
// metalness workflow (F0 = mix(0.04, base colour, metallic)). Output: linear HDR radiance, never NaN/Inf.
// main() reads the pixel's surface, then adds the environment term, the clear coat's environment lobe and the
// lights, and writes the radiance or the debug view; each step is one function below.
#include "common/bindings.glsl"
#define GLIMMER_LIGHTING_PASS 1   // lets method files read lighting-pass data (u_materials) that probes lack
#include "common/frame.glsl"
#include "common/brdf.glsl"
#include "common/footprint.glsl"
#include "common/glint_surface.glsl"
#include "environment/prefiltered_lookup.glsl"
#include "common/clearcoat.glsl"
#include "common/light_incidence.glsl"
#include "common/plane_aware_upsample.glsl"
#include "frame/method_output_check.glsl"
#include "lights/ltc.glsl"
#include "lights/area_light.glsl"
#ifdef SHADOWS
#include "shadows/shadows.glsl"
#endif

vec3 finiteOrZero(vec3 c) {
    bvec3 bad = bvec3(isnan(c.x) || isinf(c.x), isnan(c.y) || isinf(c.y), isnan(c.z) || isinf(c.z));
    return any(bad) ? vec3(0.0) : c;
}

// Radiance as it may reach the frame: finite and not negative (a negative D gave negative radiance in the EXR and
// a white PNG). Counted before this in flushMethodOutput.
vec3 plausibleRadiance(vec3 c) { return max(finiteOrZero(c), vec3(0.0)); }

// A method with lighting targets of its own (GLINT_METHOD_TARGETS; shaders/glints/README.md, "Lighting targets")
// declares them at locations 2.. and the hooks glintTakeLightGlint, glintScaleTargets and glintWriteTargets.
#include GLINT_METHOD_FILE
#include IBL_MODE_FILE

layout(binding = UNIT_GBUFFER_UV_DUVDX) uniform sampler2D g_uvDuvdx;
layout(binding = UNIT_GBUFFER_DUVDY_MATERIAL) uniform sampler2D g_duvdyMaterial;
layout(binding = UNIT_GBUFFER_NORMAL_ALPHA) uniform sampler2D g_normalAlpha;
layout(binding = UNIT_GBUFFER_TANGENT_METALLIC) uniform sampler2D g_tangentMetallic;
layout(binding = UNIT_GBUFFER_BASE_COLOR_MASK) uniform sampler2D g_baseColorMask;
layout(binding = UNIT_GBUFFER_DEPTH) uniform sampler2D g_depth;
layout(binding = UNIT_GBUFFER_CLEARCOAT) uniform sampler2D g_clearcoat;   // KHR_materials_clearcoat (gbuffer.frag)
// rgb: occlusion of the environment / ambient term, a: visibility (shaders/ao/ao_resolve.frag; white when off)
layout(binding = UNIT_AMBIENT_OCCLUSION) uniform sampler2D u_ambientOcclusion;
#ifdef GLINT_SLOPE_COVARIANCE
// G-buffer target 6: the LEAN-filtered normal map's slope covariance (GlintMethod::slopeCovariance).
layout(binding = UNIT_GBUFFER_SLOPE_COVARIANCE) uniform sampler2D g_slopeCovariance;
#endif

// The depth test before the shader: with lighting.split_glinty each pixel passes the GL_EQUAL test of one of the
// two programs only (render/frame/lighting_pass.h), but the method output check's atomics (frame/
// method_output_check.glsl) are side effects, which make the driver run the shader and test depth after it: every
// pixel then paid for both programs (llvmpipe, court 320x180: lighting 189 -> 85 ms with this). Nothing here
// writes depth.
layout(early_fragment_tests) in;
in vec2 v_ndc;
layout(location = 0) out vec4 o_color;
// The part of o_color that is the lights' specular on glinty materials: the TAA resolve keeps it out of its
// neighbourhood clipping (shaders/image/taa_resolve.frag). Written only where TAA attaches a target.
layout(location = 1) out vec4 o_glintPart;

// TAA with taa.stable_glints: the point of the tangent plane through `anchor` (normal n) seen through the screen
// position `screen` (pixels) of this frame. Falls back to `anchor` for rays almost parallel to the plane.
vec3 tangentPlanePoint(vec2 screen, vec3 anchor, vec3 n) {
    vec2 ndc = screen / vec2(u_viewport.xy) * 2.0 - 1.0;
    vec4 near = u_inverseViewProjection * vec4(ndc, 1.0, 1.0);   // reversed Z: depth 1 is the near plane
    vec3 direction = normalize(near.xyz / near.w - u_cameraPosition.xyz);
    float cosine = dot(direction, n);
    if (abs(cosine) < 1e-3) return anchor;
    float t = dot(anchor - u_cameraPosition.xyz, n) / cosine;
    return t > 0.0 ? u_cameraPosition.xyz + direction * t : anchor;
}

// Moves the glint footprint of a jittered pixel to its unjittered centre. The jittered image is the unjittered one
// moved by u_jitter.xy pixels, so that centre lies at pixel + 0.5 + u_jitter.xy here. The UV is taken as an affine
// map of the tangent plane (exact for planar mappings), fitted to the G-buffer's derivatives at the jittered centre;
// the unjittered centre and its one-pixel neighbours then give the UV, its derivatives (which change across the
// screen under perspective: at grazing angles a half-pixel shift changes the footprint by 10-20%) and the position.
void unjitterGlintFootprint(inout GlintSurface s, inout vec3 position) {
    vec2 centre = vec2(s.pixel) + 0.5;
    vec3 p = tangentPlanePoint(centre, position, s.n);
    vec3 dx = tangentPlanePoint(centre + vec2(1.0, 0.0), position, s.n) - p;
    vec3 dy = tangentPlanePoint(centre + vec2(0.0, 1.0), position, s.n) - p;
    mat2 planeDerivatives = mat2(vec2(dot(dx, s.t), dot(dx, s.b)), vec2(dot(dy, s.t), dot(dy, s.b)));
    if (abs(determinant(planeDerivatives)) < 1e-12) return;
    mat2 planeToUv = mat2(s.duvdx, s.duvdy) * inverse(planeDerivatives);
    vec2 moved = centre + u_jitter.xy;
    vec3 q = tangentPlanePoint(moved, position, s.n);
    vec3 qx = tangentPlanePoint(moved + vec2(1.0, 0.0), position, s.n) - q;
    vec3 qy = tangentPlanePoint(moved + vec2(0.0, 1.0), position, s.n) - q;
    s.uv += planeToUv * vec2(dot(q - p, s.t), dot(q - p, s.b));
    s.duvdx = planeToUv * vec2(dot(qx, s.t), dot(qx, s.b));
    s.duvdy = planeToUv * vec2(dot(qy, s.t), dot(qy, s.b));
    position = q;
}

#ifdef GLINT_SURFACE_DERIVATIVES
// For methods that filter their NDF over the pixel's range of half vectors (GlintMethod::surfaceDerivatives;
// Chermain et al. 2021's GGAA): the screen-space derivatives of the surface, which a full-screen pass cannot take
// with dFdx. Of the two neighbours along each axis the one nearer the pixel's tangent plane (|offset . n| over
// |offset| below 0.5) gives a one-sided difference of the G-buffer's position and shading normal; across an edge
// (no such neighbour) the position moves in the tangent plane and the normal does not change.
void glintSurfaceDerivatives(inout GlintSurface s, ivec2 pixel, vec3 gbufferPosition, vec3 position) {
    s.viewDistance = distance(u_cameraPosition.xyz, position);
    vec2 centre = vec2(pixel) + 0.5;
    vec3 planeCentre = tangentPlanePoint(centre, position, s.n);
    for (int axis = 0; axis < 2; ++axis) {
        ivec2 step = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
        vec3 dp = tangentPlanePoint(centre + vec2(step), position, s.n) - planeCentre;
        vec3 dn = vec3(0.0);
        float best = 0.5;
        for (int side = -1; side <= 1; side += 2) {
            ivec2 q = pixel + side * step;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, u_viewport.xy))) continue;
            float d = texelFetch(g_depth, q, 0).r;
            if (d <= 0.0) continue;
            vec3 offset = worldPosition(q, d) - gbufferPosition;
            float deviation = abs(dot(offset, s.n)) / max(length(offset), 1e-20);
            if (deviation < best) {
                best = deviation;
                dp = float(side) * offset;
                dn = float(side) * (normalize(texelFetch(g_normalAlpha, q, 0).xyz) - s.n);
            }
        }
        if (axis == 0) { s.dpdx = dp; s.dndx = dn; } else { s.dpdy = dp; s.dndy = dn; }
    }
}
#endif
// Solid angle (sr) of a punctual or directional light seen from `position` (Kneiphof & Klein 2024: every light has
// one): the sun's disk (spotOffsetRange.z, from its angular diameter), a point or spot light's sphere of its
// radius (spotOffsetRange.z; 0 for a punctual light).
float punctualSolidAngle(GpuLight light, vec3 position) {
    if (light.vectorType.w < 0.5) return light.spotOffsetRange.z;
    vec3 d = light.vectorType.xyz - position;
    float sin2 = min(light.spotOffsetRange.z * light.spotOffsetRange.z / max(dot(d, d), 1e-12), 1.0);
    return 2.0 * PI * (1.0 - sqrt(1.0 - sin2));
}

// The glint factor of an area light (multiplies its smooth LTC specular; expectation 1). Methods that define
// GLINT_AREA_LIGHTS compute it themselves (glintAreaFactor); for the others it is their NDF at the light's centre
// direction over the smooth NDF there: the light's glints are those of a point light at its centre
// (shaders/glints/README.md "Extended lights").
vec3 areaGlintFactor(GlintPixel glint, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
#ifdef GLINT_AREA_LIGHTS
    return glintAreaFactor(glint, s, h, wi, wo);
#else
    float smoothD = D_smooth(h, s.alpha, s.ndf);
    if (!(smoothD > 1e-30)) return vec3(1.0);
#ifdef GLINT_COLOR_D
    return glintColorD(glint, s, h, wi, wo) / smoothD;
#else
    return vec3(glintD(glint, s, h, wi, wo) / smoothD);
#endif
#endif
}

// TAA with taa.stable_glints: the shading frame (normal, tangent) at the unjittered pixel centre, to first order:
// this pixel's G-buffer frame plus the jitter times its screen derivatives, taken from the neighbours on the same
// surface (same material, depth within 5%; one-sided at an edge, none across it). A glint lies in a cone of a few
// hundredths of a radian around h, and at render scale 0.25 the normal of the atrium's spheres turns by about that
// much across half a pixel: with the jittered normal, sparkles came and went from frame to frame on a still camera
// (issue 39, measured in docs/window.md). The error left is second order in the jitter.
vec3 sameSurfaceDerivative(sampler2D frameTexture, ivec2 pixel, ivec2 axis, int materialId, float depth, vec3 centre) {
    ivec2 size = textureSize(g_depth, 0);
    vec3 sum = vec3(0.0);
    float sides = 0.0;
    for (int side = -1; side <= 1; side += 2) {
        ivec2 q = pixel + side * axis;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        float d = texelFetch(g_depth, q, 0).r;
        if (d <= 0.0 || abs(d - depth) > 0.05 * depth) continue;
        if (int(texelFetch(g_duvdyMaterial, q, 0).z + 0.5) != materialId) continue;
        sum += float(side) * (texelFetch(frameTexture, q, 0).xyz - centre);
        sides += 1.0;
    }
    return sides > 0.0 ? sum / sides : vec3(0.0);
}

void unjitterGlintFrame(inout GlintSurface s, float depth, float handedness) {
    vec3 n = texelFetch(g_normalAlpha, s.pixel, 0).xyz, t = texelFetch(g_tangentMetallic, s.pixel, 0).xyz;
    vec2 j = u_jitter.xy;
    n += j.x * sameSurfaceDerivative(g_normalAlpha, s.pixel, ivec2(1, 0), s.materialId, depth, n) +
         j.y * sameSurfaceDerivative(g_normalAlpha, s.pixel, ivec2(0, 1), s.materialId, depth, n);
    t += j.x * sameSurfaceDerivative(g_tangentMetallic, s.pixel, ivec2(1, 0), s.materialId, depth, t) +
         j.y * sameSurfaceDerivative(g_tangentMetallic, s.pixel, ivec2(0, 1), s.materialId, depth, t);
    if (dot(n, n) < 1e-8) return;
    s.n = normalize(n);
    vec3 tangent = t - s.n * dot(s.n, t);
    if (dot(tangent, tangent) < 1e-8) return;
    s.t = normalize(tangent);
    s.b = handedness * cross(s.n, s.t);
}

// The pixel as the G-buffer holds it (layout in frame/gbuffer.frag), with what the shading needs of its material.
struct PixelSurface {
    GlintSurface s;
    bool glinty;
    vec3 gbufferPosition;   // at the G-buffer's own (possibly jittered) pixel centre
    vec3 position;          // where the pixel is shaded (moved for glints by TAA's unjittering)
    vec3 baseColor;
    float metallic;
    int materialId;
};

PixelSurface readPixelSurface(ivec2 pixel, float depth) {
    vec4 uvDuvdx = texelFetch(g_uvDuvdx, pixel, 0);
    vec4 duvdyMaterial = texelFetch(g_duvdyMaterial, pixel, 0);
    vec4 normalAlpha = texelFetch(g_normalAlpha, pixel, 0);
    vec4 tangentMetallic = texelFetch(g_tangentMetallic, pixel, 0);
    vec4 baseColorMask = texelFetch(g_baseColorMask, pixel, 0);

    PixelSurface p;
    p.materialId = int(duvdyMaterial.z + 0.5);
    GpuMaterial material = u_materials[p.materialId];
    g_glintMaterial = p.materialId;   // the method's P_<NAME> read this material's parameters
    p.s.uv = uvDuvdx.xy;
    p.s.duvdx = uvDuvdx.zw;
    p.s.duvdy = duvdyMaterial.xy;
    p.s.alpha = normalAlpha.w;
    p.s.ndf = int(material.alphaMetallicNdfGlinty.z + 0.5);
    p.s.densityScale = material.densityCutoff.x * baseColorMask.a;
    p.s.materialId = p.materialId;
    p.s.pixel = pixel;
    p.s.n = normalize(normalAlpha.xyz);
    p.s.t = normalize(tangentMetallic.xyz - p.s.n * dot(p.s.n, tangentMetallic.xyz));
    p.s.b = duvdyMaterial.w * cross(p.s.n, p.s.t);
    clearGlintSurfaceExtras(p.s);
#ifdef NON_GLINTY_PIXELS
    // The pixels lighting_class.frag did not mark glinty (render/frame/lighting_pass.h): the compiler drops the
    // method's code, and every other term is this shader's own.
    p.glinty = false;
#else
    p.glinty = material.alphaMetallicNdfGlinty.w > 0.5;
#endif
    p.gbufferPosition = worldPosition(pixel, depth);
    p.position = p.gbufferPosition;
    // TAA jitters the projection by u_jitter.xy pixels. Glint methods filter their NDF over the pixel footprint
    // (duv/dx, duv/dy; shaders/glints/README.md), and that footprint must be the same in every frame of a still
    // camera: averaged over 16 jittered footprints and view directions, each sparkle would be supersampled a
    // second time and lose its peak (docs/image.md, "glints"). So with taa.stable_glints a glinty pixel is shaded
    // at its unjittered centre: UV, UV derivatives and position (hence the view and light directions) move to
    // the tangent-plane point of the unjittered ray. Coverage, normal and base colour stay jittered, so the
    // geometric edges of glinty surfaces are still anti-aliased.
    if (p.glinty && u_jitter.z > 0.5) {
        unjitterGlintFrame(p.s, depth, duvdyMaterial.w);
        unjitterGlintFootprint(p.s, p.position);
    }
    p.s.position = p.position;
#if defined(GLINT_SLOPE_COVARIANCE) && !defined(NON_GLINTY_PIXELS)
    if (p.glinty) p.s.slopeCovariance = texelFetch(g_slopeCovariance, pixel, 0).xyz;
#endif
#if defined(GLINT_SURFACE_DERIVATIVES) && !defined(NON_GLINTY_PIXELS)
    if (p.glinty) glintSurfaceDerivatives(p.s, pixel, p.gbufferPosition, p.position);
#endif
    // lighting.glint_footprint=output below render scale 1: the glint is filtered over an output pixel's footprint
    // at this render pixel's centre (after the unjittering above, which moves by render pixels), the sparkle an
    // output pixel would show; the mean is unchanged (every method keeps E[D] = D at any footprint).
    if (p.glinty && u_jitter.w > 0.0 && u_jitter.w < 1.0) {
        p.s.duvdx *= u_jitter.w;
        p.s.duvdy *= u_jitter.w;
#if defined(GLINT_SURFACE_DERIVATIVES) && !defined(NON_GLINTY_PIXELS)
        p.s.dpdx *= u_jitter.w;
        p.s.dpdy *= u_jitter.w;
        p.s.dndx *= u_jitter.w;
        p.s.dndy *= u_jitter.w;
#endif
    }
    p.baseColor = baseColorMask.rgb;
    p.metallic = tangentMetallic.w;
    return p;
}

// Ambient occlusion of the environment term (docs/ambient_occlusion.md): rgb the factor, a the visibility. At
// ao.half_res the factor is interpolated from every second pixel (common/plane_aware_upsample.glsl); the taps are
// shared with the shadow mask when both run at half resolution (`maskTaps`, valid when `maskTapsValid`).
vec4 ambientOcclusion(PixelSurface p, UpsampleTaps maskTaps, bool maskTapsValid) {
    ivec2 aoSize = textureSize(u_ambientOcclusion, 0);
    int aoStep = aoSize.x >= u_viewport.x ? 1 : 2;   // AmbientOcclusion::step(): a halved target is ceil(w / 2) wide
    if (aoSize == ivec2(1)) return texelFetch(u_ambientOcclusion, ivec2(0), 0);   // white: AO off
    if (aoStep == 1) return texelFetch(u_ambientOcclusion, p.s.pixel, 0);
    UpsampleTaps aoTaps;
    bool sharedTaps = false;
#ifdef SHADOWS
    sharedTaps = maskTapsValid && u_shadowMask.x == aoStep;
    if (sharedTaps) aoTaps = maskTaps;
#endif
    if (!sharedTaps)
        aoTaps = planeAwareTaps(p.s.pixel, p.gbufferPosition, p.s.n, g_depth, u_viewport.xy, aoStep, aoSize - 1);
    vec4 occlusion = vec4(0.0);
    for (int k = 0; k < 4; ++k) occlusion += aoTaps.weight[k] * texelFetch(u_ambientOcclusion, aoTaps.texel[k], 0);
    return occlusion / aoTaps.total;
}

// The clear coat's environment lobe in every IBL mode: split sum at the coat's roughness along its mirror direction,
// from the prefiltered map and the reflection probes where the frame binds them (count 0 otherwise); GGX table with
// F0 = 1 (the Fresnel is in the weight). Without an environment the constant ambient is reflected with the lobe's
// albedo taken as 1.
vec3 clearcoatEnvironment(Clearcoat coat, vec3 position, vec3 toEye) {
    vec3 coatEnvironment = u_skyColor.rgb * u_exposure.z;
    if (envEnabled()) {
        vec2 ab = envBrdf(clamp(coat.nDotV, 1e-4, 1.0), coat.alpha, NDF_GGX);
        coatEnvironment = envPrefilteredAt(position, reflect(-toEye, coat.n), coat.alpha, NDF_GGX) * (ab.x + ab.y);
    }
    return coatEnvironment;
}

// Whether the pixel has a clear coat. Without SCENE_CLEARCOAT (no coated material in the scene:
// render/frame/lighting_pass.h) it is the constant false and the coat's terms compile away; llvmpipe would run
// them under an all-off mask otherwise.
bool hasClearcoat(Clearcoat coat) {
#ifdef SCENE_CLEARCOAT
    return coat.weight > 0.0;
#else
    return false;
#endif
}

// What the lights add besides the radiance: the parts other targets and the debug views need.
struct LightSum {
    vec3 glintPart;         // the lights' specular on glinty pixels (inside radiance; TAA's glint part)
    float firstLightD;      // the glint AOV: D of light 0
    float firstLightVisibility;
    MethodOutputTally tally;   // what the method's D looked like (frame/method_output_check.glsl)
};

// Adds every light's diffuse and specular to `radiance` (the base layer) and its coat lobe to `coatRadiance`.
LightSum shadeLights(PixelSurface p, GlintPixel glint, mat3 worldToShading, vec3 toEye, vec3 wo, vec3 diffuseAlbedo,
                     vec3 f0, Clearcoat coat, UpsampleTaps maskTaps, inout vec3 radiance, inout vec3 coatRadiance) {
    LightSum sum;
    sum.glintPart = vec3(0.0);
    sum.firstLightD = 0.0;
    sum.firstLightVisibility = 0.0;
    sum.tally = methodOutputTally();
    GlintSurface s = p.s;
    const bool sampledPixel = methodOutputSampled(s.pixel);
    bool coated = hasClearcoat(coat);
    int view = u_viewport.w;
    int lightCount = int(u_exposure.y);
#ifdef SHADOWS
    vec4 maskVisibility[MAX_SHADOW_SLOTS / 4];
    // At the G-buffer's own position (TAA's glint unjittering may have moved `position`), as the mask's samples.
    shadowMaskVisibility(s.pixel, maskTaps, maskVisibility);
#endif
    int areaLightCount = int(u_exposure.w);   // the last ones (render/gpu_scene.h)
    // Punctual and directional lights. Area lights follow in a loop of their own: llvmpipe executes both sides of a
    // branch, so one loop would make every light pay for the LTC integrals. The loops of this function test their
    // condition at the bottom (lights/ltc.glsl ltcLoopCount: a loop tested at its top cost llvmpipe one more pass
    // through its body); `continue` goes to that test.
    int punctualCount = lightCount - areaLightCount;
    int i = 0;
    if (punctualCount > 0) do {
        vec3 towardLight, irradiance;
        lightIncidence(u_lights[i], p.position, towardLight, irradiance);
        vec3 wi = worldToShading * towardLight;
        // A coated pixel may see a light through its coat that its (normal-mapped) base faces away from.
        bool coatLit = coated && dot(coat.n, towardLight) > 0.0 && coat.nDotV > 0.0;
        if ((wi.z <= 0.0 || wo.z <= 0.0) && !coatLit) continue;
        // Shadows: the light's whole contribution, diffuse and (glint) specular, scales with its visibility
        // (shadows/shadows.glsl); a fully shadowed light is skipped, except for the glint view's D.
#ifdef SHADOWS
        // From the shadow mask (render/shadows/shadow_mask_pass.h: the maps are filtered there, at a quarter of the
        // pixels by default).
        float visibility = maskedLightVisibility(i, maskVisibility);
#else
        float visibility = 1.0;   // shadow.enabled=0 (render/frame/lighting_pass.h)
#endif
        if (i == 0) sum.firstLightVisibility = visibility;
        if (visibility <= 0.0 && !(i == 0 && view == VIEW_GLINT)) continue;
        irradiance *= visibility;
        if (coatLit) coatRadiance += coat.weight * clearcoatLobeCosine(coat, towardLight, toEye) * irradiance;
        if (wi.z <= 0.0 || wo.z <= 0.0) continue;
        vec3 h = normalize(wi + wo);
#ifdef GLINT_SURFACE_DERIVATIVES
        g_glintLightDistance = u_lights[i].vectorType.w < 0.5 ? 0.0 : distance(u_lights[i].vectorType.xyz, p.position);
#endif
        // The light's size for the glint methods (GlintLight): its solid angle and the integral of D(h) / (4 |l.h|)
        // over it, D(h) Omega / (4 (l.h)) for a light this small (Kneiphof & Klein 2024, Sec. 4.3).
        g_glintLight.area = false;
        g_glintLight.solidAngle = punctualSolidAngle(u_lights[i], p.position);
        g_glintLight.ndfIntegral = D_smooth(h, s.alpha, s.ndf) * g_glintLight.solidAngle / (4.0 * max(dot(wi, h), 1e-4));
#ifdef GLINT_COLOR_D
        // Methods with per-glint colours return an RGB NDF (shaders/glints/README.md).
        vec3 colorD = p.glinty ? glintColorD(glint, s, h, wi, wo) : vec3(D_smooth(h, s.alpha, s.ndf));
        if (p.glinty) tallyColorD(sum.tally, colorD, sampledPixel, h, s.alpha, s.ndf);
        float D = dot(colorD, vec3(1.0 / 3.0));
        vec3 specular = cookTorranceSpecular(1.0, wi, wo, h, s.alpha, s.ndf, f0) * colorD;
#else
        float D = p.glinty ? glintD(glint, s, h, wi, wo) : D_smooth(h, s.alpha, s.ndf);
        if (p.glinty) tallyD(sum.tally, D, sampledPixel, h, s.alpha, s.ndf);
        vec3 specular = cookTorranceSpecular(D, wi, wo, h, s.alpha, s.ndf, f0);
#endif
        if (i == 0) sum.firstLightD = D;
#ifdef GLINT_METHOD_TARGETS
        // The method keeps its light glints in its own target (its passes add them later).
        if (p.glinty && glintTakeLightGlint(specular * irradiance * wi.z)) specular = vec3(0.0);
#else
        if (p.glinty) sum.glintPart += specular * irradiance * wi.z;
#endif
        radiance += (diffuseAlbedo * INV_PI + specular) * irradiance * wi.z;
    } while (++i < punctualCount);

    // Area lights (lights/area_light.glsl): Lambertian emitters of radiance L; diffuse = albedo x L x their form
    // factor, specular = L x (f0 A + B) x the specular LTC's integral over them (Heitz et al. 2016, Eq. 7 and
    // Sec. 4.3), times the glint factor of the method on glinty pixels (Kneiphof & Klein 2024, Sec. 4: the glint
    // factor multiplies the LTC specular).
    if (areaLightCount > 0 && wo.z > 0.0) {
        LtcPixel ltc = ltcSetup(s.n, toEye, s.alpha, s.ndf);   // once per pixel, shared by the area lights
        vec3 specularAlbedo = f0 * ltc.splitSum.x + ltc.splitSum.y;
        int firstArea = lightCount - areaLightCount;
#ifdef SHADOWS
        if (firstArea == 0) sum.firstLightVisibility = maskedLightVisibility(0, maskVisibility);
#else
        if (firstArea == 0) sum.firstLightVisibility = 1.0;
#endif
        vec3 coatN = coated ? coat.n : s.n;
        // The lights that reach this pixel, 32 to a word: in range, facing it, above its horizon (or its coat's) and
        // not wholly shadowed (areaLightReaches). The loop below runs over the set bits only: llvmpipe executes
        // every light of a branchy loop under a mask, but a loop ends when no pixel of the SIMD group has work
        // left, so a light that none of the group's pixels sees costs only this test, not its integrals.
        for (int word = firstArea; word < lightCount; word += 32) {
            uint pending = 0u;
            int last = min(word + 32, lightCount);
            int candidate = word;
            do {
                bool reaches = areaLightReaches(u_lights[candidate], p.position, s.n, coatN);
#ifdef SHADOWS
                reaches = reaches && maskedLightVisibility(candidate, maskVisibility) > 0.0;
#endif
                if (reaches) pending |= 1u << uint(candidate - word);
            } while (++candidate < last);
            if (pending != 0u) do {
                int bit = findLSB(pending);
                pending &= pending - 1u;
                i = word + bit;
                AreaLightGeometry g = areaLightGeometry(u_lights[i], p.position, ltc.toFrame);
#ifdef SHADOWS
                float visibility = maskedLightVisibility(i, maskVisibility);
#else
                float visibility = 1.0;
#endif
                vec3 L = u_lights[i].colorIntensity.rgb * (u_lights[i].colorIntensity.a * g.window * visibility);
                // The diffuse form factor (M = identity) and the specular LTC's integral, in one loop (one copy of
                // the integrals in the program; ltcLoopCount keeps the compiler from unrolling it). Spheres take
                // the cap's exact form factor instead (the disk of their silhouette gives the same, less exactly),
                // so their loop starts at the specular integral.
                bool sphere = g.sinSigma2 > 0.0;
                float integrals[2];
                integrals[0] = sphere ? ltcCapCosine(g.sinSigma2, dot(g.towardCentre, s.n)) : 0.0;
                int k = sphere ? 1 : 0;
                do {
                    integrals[k] = ltcAreaIntegral(g.shape, g.centre, g.halfU, g.halfV,
                                                   k == 0 ? mat3(1.0) : ltc.invSpecular);
                    ++k;
                } while (k < ltcLoopCount(2));
                float diffuse = integrals[0];
                float specularIntegral = integrals[1];
                vec3 specular = specularAlbedo * specularIntegral;
                if (p.glinty && specularIntegral > 0.0) {
                    // The light's representative direction is its centre's (Kneiphof & Klein's demo): it picks the
                    // angular cell of deliot2023's grid and the NDF value of the fallback.
                    vec3 wi = worldToShading * g.towardCentre;
                    vec3 h = normalize(vec3(wi.xy, max(wi.z, 1e-4)) + wo);
                    g_glintLight = GlintLight(true, g.solidAngle, ltc.ndfOnly * specularIntegral, specularIntegral,
                                              g.shape, g.centre, g.halfU, g.halfV, ltc.invNdfOnly, ltc.ndfOnly);
                    specular *= areaGlintFactor(glint, s, h, wi, wo);
#ifdef GLINT_METHOD_TARGETS
                    // The method keeps its light glints in its own target (its passes add them later).
                    if (glintTakeLightGlint(specular * L)) specular = vec3(0.0);
#else
                    sum.glintPart += specular * L;
#endif
                }
                radiance += (diffuseAlbedo * diffuse + specular) * L;
                if (coated && coat.nDotV > 0.0 && dot(coat.n, g.towardCentre) > 0.0) {
                    // The coat's lobe sees the light as a point of its intensity at the centre (lightIncidence).
                    vec3 towardLight, irradiance;
                    lightIncidence(u_lights[i], p.position, towardLight, irradiance);
                    coatRadiance += coat.weight * clearcoatLobeCosine(coat, towardLight, toEye) * irradiance * visibility;
                }
            } while (pending != 0u);
        }
    }
    return sum;
}

// --aov views (render/aov.h).
vec4 debugView(int view, PixelSurface p, GlintPixel glint, vec3 radiance, LightSum lights, vec4 occlusion,
               vec4 coatTexelView) {
    GlintSurface s = p.s;
    switch (view) {
        case VIEW_ALBEDO: return vec4(p.baseColor, 1.0);
        case VIEW_NORMAL: return vec4(s.n, 1.0);
        case VIEW_DEPTH: return vec4(vec3(distance(p.position, u_cameraPosition.xyz)), 1.0);
        case VIEW_UV: return vec4(s.uv, 0.0, 1.0);
        case VIEW_DUVDX: return vec4(s.duvdx, 0.0, 1.0);
        case VIEW_DUVDY: return vec4(s.duvdy, 0.0, 1.0);
        case VIEW_GLINT: return vec4(vec3(lights.firstLightD), 1.0);
        case VIEW_FOOTPRINT: return glintFootprintAOV(glint, s);
        case VIEW_TANGENT: return vec4(s.t, dot(s.b, cross(s.n, s.t)));   // a: the bitangent's sign (G-buffer)
        case VIEW_ROUGHNESS_METALLIC: return vec4(s.alpha, p.metallic, float(p.materialId), 1.0);
        case VIEW_EXTRA: return glintExtraAOV(glint, s);
        case VIEW_AO: return vec4(vec3(occlusion.a), 1.0);
        case VIEW_SHADOW: return vec4(vec3(lights.firstLightVisibility), 1.0);
        case VIEW_CLEARCOAT: return coatTexelView;
        default: return vec4(radiance, 1.0);
    }
}

// A pixel where nothing was drawn (reversed-Z clear value): the environment's radiance along the view ray (through
// the near plane, depth 1), else the sky colour.
void writeBackground(ivec2 pixel, int view) {
    vec3 sky = envEnabled() ? envBackground(normalize(worldPosition(pixel, 1.0) - u_cameraPosition.xyz))
                            : u_skyColor.rgb;
    o_color = vec4(view == VIEW_FINAL ? finiteOrZero(sky) : vec3(0.0), 0.0);
    o_glintPart = vec4(0.0);
#ifdef GLINT_METHOD_TARGETS
    glintWriteTargets(false, false);
#endif
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(g_depth, pixel, 0).r;
    int view = u_viewport.w;
    if (depth <= 0.0) {
        writeBackground(pixel, view);
        return;
    }
    PixelSurface p = readPixelSurface(pixel, depth);
    vec3 toEye = normalize(u_cameraPosition.xyz - p.position);
    mat3 worldToShading = transpose(mat3(p.s.t, p.s.b, p.s.n));
    vec3 wo = worldToShading * toEye;
    vec3 f0 = mix(vec3(0.04), p.baseColor, p.metallic);
    vec3 diffuseAlbedo = (1.0 - p.metallic) * p.baseColor;

    // KHR_materials_clearcoat (common/clearcoat.glsl): the coat's own lobe goes to coatRadiance; the base radiance
    // (all of it, the method's glints included) is scaled by 1 - weight at the end. Uncoated pixels (weight 0)
    // skip both, so their radiance is the uncoated shader's bit for bit.
    vec4 coatTexel = texelFetch(g_clearcoat, pixel, 0);
    Clearcoat coat = clearcoatFromGBuffer(coatTexel, toEye);
    vec4 coatTexelView = vec4(coatTexel.zw, coat.weight, 1.0);
    bool coated = hasClearcoat(coat);

    // Per-pixel glint setup, computed once and shared by every light (Deliot & Belcour 2023, Sec. 7). The
    // non-glinty variant never reads it (its debug views are not split off: render/frame/lighting_pass.h).
#ifdef NON_GLINTY_PIXELS
    GlintPixel glint;
#else
    GlintPixel glint = glintSetup(p.s);
#endif

    // The shadow mask's interpolation taps, at the G-buffer's own position as the mask's samples.
    UpsampleTaps maskTaps;
    bool maskTapsValid = false;
#ifdef SHADOWS
    if (u_shadowMask.x != 1) {
        maskTaps = planeAwareTaps(pixel, p.gbufferPosition, p.s.n, g_depth, u_viewport.xy, u_shadowMask.x,
                                  shadowMaskLastTexel());
        maskTapsValid = true;
    }
#endif
    // Environment lighting by the selected IBL mode (shaders/environment/ibl/README.md), or the constant ambient
    // when the environment is off (--env none). Ambient occlusion darkens this term only, never the lights.
    vec4 occlusion = ambientOcclusion(p, maskTaps, maskTapsValid);
    // A method may widen the roughness the environment sees (GLINT_ENVIRONMENT_ALPHA, shaders/glints/README.md:
    // Chermain et al. 2021 light the environment with the LEAN-filtered roughness).
    GlintSurface environmentSurface = p.s;
#if defined(GLINT_ENVIRONMENT_ALPHA) && !defined(NON_GLINTY_PIXELS)
    if (p.glinty) environmentSurface.alpha = glintEnvironmentAlpha(glint, p.s);
#endif
    vec3 radiance = occlusion.rgb * (envEnabled()
        ? iblRadiance(glint, environmentSurface, wo, toEye, worldToShading, diffuseAlbedo, f0, p.glinty, u_sample.x)
        : u_skyColor.rgb * u_exposure.z * diffuseAlbedo);
    vec3 coatRadiance = vec3(0.0);
    if (coated) coatRadiance += occlusion.rgb * coat.weight * clearcoatEnvironment(coat, p.position, toEye);

    LightSum lights = shadeLights(p, glint, worldToShading, toEye, wo, diffuseAlbedo, f0, coat, maskTaps, radiance,
                                  coatRadiance);
    // The environment's glints (the IBL mode's, inside `radiance`: environment/ibl/prefiltered.glsl) join the
    // lights' in the glint part.
    vec3 glintPart = lights.glintPart + occlusion.rgb * g_environmentGlintPart;
    if (coated) {
        float baseShare = 1.0 - coat.weight;
        radiance = radiance * baseShare + coatRadiance;
        glintPart *= baseShare;
#ifdef GLINT_METHOD_TARGETS
        glintScaleTargets(baseShare);
#endif
    }

    vec4 result = debugView(view, p, glint, radiance, lights, occlusion, coatTexelView);
    // Debug views pass signed values through (normals); the final radiance is finite and non-negative.
    vec3 shown = view == VIEW_FINAL ? plausibleRadiance(result.rgb) : finiteOrZero(result.rgb);
    flushMethodOutput(lights.tally, view == VIEW_FINAL ? result.rgb : vec3(0.0));
    o_color = vec4(shown, isnan(result.a) || isinf(result.a) ? 0.0 : result.a);
    // Methods with lighting targets add their (blurred) glints after this pass: TAA clips them with the rest.
    bool finiteResult = all(equal(o_color.rgb, result.rgb));
    o_glintPart = vec4(view == VIEW_FINAL && finiteResult ? plausibleRadiance(glintPart) : vec3(0.0), 0.0);
#ifdef GLINT_METHOD_TARGETS
    glintWriteTargets(p.glinty, view == VIEW_FINAL);
#endif
}
