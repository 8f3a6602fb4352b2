// Prefiltered specular radiance for up to 4 roughnesses x 2 NDFs at once (split sum, Karis 2013, Eq. 3 with n = v = r):
//   L(r) = integral L(l) D(h) (n.l) dl / integral D(h) (n.l) dl,   h = normalize(l + r)
// for the NDF of this layer (0 GGX, 1 Beckmann), by quadrature over the texels of the source cube's mips rather
// than by sampling. Each target texel walks a quadtree over the source: the 4 x 4 texels of each face of a coarse
// mip are the roots, and a texel is split into its four children one mip finer while it is wider than
// u_refine x max(angle to r, lobe width 2 alpha): near the lobe the walk reaches fine texels, the tails are summed
// from coarse ones. The texels met form a partition of the sphere, so nothing is counted twice or missed.
// A texel's integral of radiance and its solid angle are exact sums over the level-0 texels it covers (the chains
// of shaders/environment/radiance_centroid.comp); its weight is taken at the luminance-weighted mean direction of those
// texels, so a lamp of a few texels inside a coarse texel is weighted where it is, not at the texel's centre (the
// first-order error of a midpoint rule vanishes). The normalisation uses the texel centre (the lobe's own
// integral, independent of the map).
// Why not filtered importance sampling (Krivanek & Colbert 2008), which this replaced: with a fixed point set per
// texel, a lamp of a few texels (studio_small_03: up to 3568 against a mean of 1.9) is hit or missed and read
// from box mips it is spread over, and the levels came out up to 2x off per texel against quadrature
// (docs/environment.md, "Prefiltered levels").
// All four channels are filtered: a reflection probe's alpha is its coverage by geometry (sky texels 0), which the
// lighting pass blends with the distant environment (render/probes/reflection_probes.h); the environment's alpha is 1.
// One walk serves every lobe of a dispatch (the rungs of one mip, both NDFs): it is refined for the narrowest lobe
// and for the Beckmann tails and horizons of all of them, and each leaf is weighted once per lobe; the walk, not
// the weighting, is the cost, so this is 3-4x cheaper than a walk per lobe and no less accurate for any of them.
#include "environment/env_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0) uniform sampler2DArray u_weighted;   // radiance x solid angle, box mips (x 4^m: sums)
layout(binding = 1) uniform sampler2DArray u_centroid;   // rgb luminance x solid angle x direction, a solid angle
layout(rgba32f, binding = 0) uniform writeonly imageCubeArray u_target;  // one mip, all layers
layout(location = 0) uniform int u_size;          // face size of the target
layout(location = 1) uniform vec4 u_alphas;       // the dispatch's roughnesses, ascending; u_count <= LOBE_ALPHAS
layout(location = 2) uniform int u_ndfMask;       // bit 0 GGX, bit 1 Beckmann
layout(location = 3) uniform int u_rootMip;       // source mip whose texels are the quadtree's roots
layout(location = 4) uniform int u_sourceSize;    // face size of source level 0
layout(location = 5) uniform float u_refine;      // split while texel width > u_refine x max(angle, lobe width)
layout(location = 6) uniform ivec4 u_layerFaces[2];   // [ndf][i]: target layer-face of face 0 for lobe (ndf, i)
layout(location = 8) uniform float u_horizonWidth;   // texels wider than this are split on the horizon
layout(location = 9) uniform int u_count;

// LOBE_ALPHAS (1, 2 or 4, defined by environment/cube_prefilter.cpp) sizes the per-lobe registers: a single-lobe
// dispatch compiled for 4 roughnesses ran 2.5x slower on llvmpipe (the probes' prefilter).
#ifndef LOBE_ALPHAS
#define LOBE_ALPHAS 4
#endif

// Weight of direction l for the lobe around r: D(h) (n.l) with n = r (0 behind the surface).
float lobeWeight(vec3 l, vec3 r, float alpha, int ndf) {
    float nDotL = dot(l, r);
    if (nDotL <= 0.0) return 0.0;
    float cosH = sqrt(0.5 * (1.0 + nDotL));   // h = normalize(l + r): cos(theta_h) = cos(theta_l / 2)
    return D_smooth(vec3(0.0, 0.0, cosH), alpha, ndf) * nDotL;
}

// Node of the walk: face 3 bits, mip 4 bits, x and y 12 bits each.
int packNode(int face, int mip, int x, int y) { return face | (mip << 3) | (x << 7) | (y << 19); }

bool hasNdf(int ndf) { return (u_ndfMask & (1 << ndf)) != 0; }

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= u_size || id.y >= u_size) return;
    vec3 r = cubeDirection(id.z, vec2(id.xy) + 0.5, u_size);
    // Capped so that the widest lobes still split their root texels near the axis: with 0.5 rad leaves the
    // midpoint rule left a constant map 1% off at alpha 0.5. The narrowest lobe sets it.
    float lobeWidth = min(2.0 * u_alphas.x, 0.6);
    // D at theta_h = 45 degrees (l on the horizon of n = r) against D at the peak, for the widest lobe.
    bool splitHorizon = false;
    float widest = u_alphas[u_count - 1];
    for (int ndf = 0; ndf < 2; ++ndf)
        if (hasNdf(ndf))
            splitHorizon = splitHorizon || D_smooth(vec3(0.0, 0.0, sqrt(0.5)), widest, ndf) /
                                               D_smooth(vec3(0.0, 0.0, 1.0), widest, ndf) > 0.001;
    bool beckmannTails = hasNdf(NDF_BECKMANN) && u_alphas[u_count - 1] > 0.05;
    int rootSize = max(u_sourceSize >> u_rootMip, 1);
    // Per NDF, per roughness; the NDF explicit and the loops of constant length LOBE_ALPHAS, so that the arrays
    // stay in registers (llvmpipe: 8 lobes indexed through one array left some texels at 0, and one lobe compiled
    // that way ran 1.5x slower than this).
    vec4 sumGgx[LOBE_ALPHAS], sumBeckmann[LOBE_ALPHAS];
    float weightGgx[LOBE_ALPHAS], weightBeckmann[LOBE_ALPHAS];
    for (int i = 0; i < LOBE_ALPHAS; ++i) {
        sumGgx[i] = sumBeckmann[i] = vec4(0.0);
        weightGgx[i] = weightBeckmann[i] = 0.0;
    }
    bool ggx = hasNdf(NDF_GGX), beckmann = hasNdf(NDF_BECKMANN);
    int stack[64];
    for (int root = 0; root < 6 * rootSize * rootSize; ++root) {
        int rootFace = root / (rootSize * rootSize);
        int rest = root - rootFace * rootSize * rootSize;
        stack[0] = packNode(rootFace, u_rootMip, rest % rootSize, rest / rootSize);
        int depth = 1;
        while (depth > 0) {
            int node = stack[--depth];
            int face = node & 7, mip = (node >> 3) & 15, x = (node >> 7) & 4095, y = (node >> 19) & 4095;
            int size = max(u_sourceSize >> mip, 1);
            vec3 centre = cubeDirection(face, vec2(x, y) + 0.5, size);
            float width = 2.0 / float(size);   // angular width at the face centre (an upper bound)
            float cosAngle = dot(centre, r);
            if (cosAngle < -1.5 * width) continue;   // the whole texel is behind the surface
            float angle = acos(clamp(cosAngle, -1.0, 1.0));
            // Also split texels that straddle the surface's horizon (n.l = 0, where the weight has a kink) down to
            // u_horizonWidth, for lobes that still weigh something there (wide GGX and Beckmann lobes).
            // Beckmann's tail falls as exp(-tan^2(theta_h) / alpha^2): its log-slope per radian of l is
            // g = tan(theta_h) (1 + tan^2) / alpha^2, far steeper than GGX's 4 / angle, so there the feature size is
            // 4 / g, where the tail still weighs 1e-4 of the peak or more at the texel's near edge (the strictest
            // over the dispatch's Beckmann lobes). Not for the two narrowest rungs (alpha 0.04, 0.05, filtered at
            // 64 x 64): it doubled their cost and took the worst error only from 5% to 1.6%; from alpha 0.06
            // (32 x 32) it is needed (studio_small_03: 15% off at alpha 0.09 without).
            float feature = angle;
            if (beckmannTails && angle > lobeWidth) {
                float t = tan(0.5 * angle);
                float nearEdge = max(angle - 0.75 * width, 0.0);
                float tNear = tan(0.5 * nearEdge);
                for (int i = 0; i < u_count; ++i) {
                    float alpha = u_alphas[i];
                    if (alpha <= 0.05) continue;
                    if (exp(-tNear * tNear / (alpha * alpha)) <= 1e-4) continue;
                    float g = t * (1.0 + t * t) / (alpha * alpha);
                    feature = min(feature, 4.0 / g);
                }
            }
            bool nearLobe = width > u_refine * max(feature, lobeWidth);
            bool onHorizon = splitHorizon && abs(cosAngle) < 0.75 * width && width > u_horizonWidth;
            if (mip > 0 && (nearLobe || onHorizon) && depth + 4 <= 64) {
                for (int c = 0; c < 4; ++c) stack[depth++] = packNode(face, mip - 1, 2 * x + (c & 1), 2 * y + (c >> 1));
                continue;
            }
            float texels = float(1 << (2 * mip));   // level-0 texels per mip-m texel: the box mean x this = the sum
            vec4 where = texelFetch(u_centroid, ivec3(x, y, face), mip);
            vec3 from = dot(where.rgb, where.rgb) > 0.0 ? normalize(where.rgb) : centre;
            vec4 radiance = texelFetch(u_weighted, ivec3(x, y, face), mip) * texels;
            float solidAngle = where.a * texels;
            for (int i = 0; i < LOBE_ALPHAS; ++i) {
                if (i >= u_count) continue;
                if (ggx) {
                    sumGgx[i] += radiance * lobeWeight(from, r, u_alphas[i], NDF_GGX);
                    weightGgx[i] += lobeWeight(centre, r, u_alphas[i], NDF_GGX) * solidAngle;
                }
                if (beckmann) {
                    sumBeckmann[i] += radiance * lobeWeight(from, r, u_alphas[i], NDF_BECKMANN);
                    weightBeckmann[i] += lobeWeight(centre, r, u_alphas[i], NDF_BECKMANN) * solidAngle;
                }
            }
        }
    }
    for (int i = 0; i < LOBE_ALPHAS; ++i) {
        if (i >= u_count) continue;
        if (ggx)
            imageStore(u_target, ivec3(id.xy, u_layerFaces[NDF_GGX][i] + id.z),
                       weightGgx[i] > 0.0 ? sumGgx[i] / weightGgx[i] : vec4(0.0));
        if (beckmann)
            imageStore(u_target, ivec3(id.xy, u_layerFaces[NDF_BECKMANN][i] + id.z),
                       weightBeckmann[i] > 0.0 ? sumBeckmann[i] / weightBeckmann[i] : vec4(0.0));
    }
}
