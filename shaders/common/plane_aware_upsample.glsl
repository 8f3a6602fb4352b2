// Reduced-resolution screen targets (shadow mask at shadow.half_res, ambient occlusion at ao.half_res): a target
// texel at `step` holds the value computed at one G-buffer pixel, its sample pixel; every other pixel interpolates
// the 2 x 2 texels around it, each with its bilinear weight divided by the square of its sample point's distance
// to this pixel's tangent plane (relative to the distance to the eye, + 1e-4), so that a pixel takes its value
// from samples on its own surface and not across a silhouette or a crease. A pixel that was a sample point gets its
// sample unchanged (the other bilinear weights are 0). Needs common/frame.glsl (worldPosition, u_cameraPosition).
#ifndef GLIMMER_PLANE_AWARE_UPSAMPLE_GLSL
#define GLIMMER_PLANE_AWARE_UPSAMPLE_GLSL

// The G-buffer pixel that texel `texel` of a target at `step` was computed at.
ivec2 reducedSamplePixel(ivec2 texel, int step, ivec2 viewport) { return min(texel * step, viewport - 1); }

// The 2 x 2 texels and their weights (not normalised: divide the weighted sum by `total`).
struct UpsampleTaps {
    ivec2 texel[4];
    float weight[4];
    float total;
};

// Taps for G-buffer `pixel` (world `position`, unit `normal`) in a target at `step` whose last texel is `last`;
// `depths` is the G-buffer depth.
UpsampleTaps planeAwareTaps(ivec2 pixel, vec3 position, vec3 normal, sampler2D depths, ivec2 viewport, int step,
                            ivec2 last) {
    UpsampleTaps taps;
    ivec2 base = pixel / step;
    vec2 f = vec2(pixel - base * step) / float(step);
    float toEye = 1.0 / max(length(position - u_cameraPosition.xyz), 1e-6);
    taps.total = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 corner = ivec2(k & 1, k >> 1);
        float bilinear = (corner.x == 0 ? 1.0 - f.x : f.x) * (corner.y == 0 ? 1.0 - f.y : f.y);
        taps.texel[k] = min(base + corner, last);
        ivec2 samplePixel = reducedSamplePixel(taps.texel[k], step, viewport);
        float sampleDepth = texelFetch(depths, samplePixel, 0).r;
        // A sky sample (depth 0) is taken as very far from the plane.
        float offPlane = sampleDepth > 0.0 ? abs(dot(worldPosition(samplePixel, sampleDepth) - position, normal)) * toEye
                                           : 1.0;
        float d = offPlane + 1e-4;
        taps.weight[k] = bilinear / (d * d);
        taps.total += taps.weight[k];
    }
    return taps;
}

#endif
