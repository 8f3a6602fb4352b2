// A glint method's statistics against the discrete-facet reference on one view (issue 36): the glint AOV (the
// first light's D, rendered with `--env none` by the caller's request) of smooth, of the method and of the
// reference (counted on the CPU from the same G-buffer), compared over blocks of pixels inside the highlight.
// Shared by tools/glint_measure.cpp and check-method's physical-material rule (material_check.h).
#pragma once
#include <string>
#include <vector>

#include "reference/discrete_facets/block_stats.h"
#include "reference/discrete_facets/facet_image.h"
#include "offscreen/offscreen.h"

namespace glimmer::facets {

// One view's glint D per pixel (bottom-up), the smooth D it is divided by, and the pixels measured (highlight:
// smooth D >= 0.1 of its peak, on a material the reference evaluates as glinty).
struct GlintFrame {
    std::vector<float> d, smooth;
    std::vector<float> lambda;   // the reference's expected reflecting facets per pixel
    std::vector<bool> inside;
    int width = 0, height = 0;
};

// The reference's frame for `request` (rendered with smooth first: that render also puts the request's materials
// and lights into the session's scene). D is expressed over the GPU's smooth D, so every method divides by the
// same image.
GlintFrame referenceGlintFrame(OffscreenSession& session, const SurfaceImage& surface, const RenderRequest& request);
// The mean over the blocks blockStats measures of the reference's expected reflecting facets per block: the
// axis on which the methods' agreement is stated (docs/glint_statistics.md).
double meanBlockLambda(const GlintFrame& reference, int block);
// `method`'s frame for the same request, measured over the reference frame's pixels.
GlintFrame methodGlintFrame(OffscreenSession& session, const std::string& method, const RenderRequest& request,
                            const GlintFrame& reference);

// The target over 4x4 blocks: CV and p99.9 / mean within 1.5x of the reference's, dark fraction within
// 0.1, mean within 5 %.
struct TargetCheck {
    double cvRatio = 0.0, p999Ratio = 0.0, darkDifference = 0.0, meanRatio = 0.0;
    bool cv = false, p999 = false, dark = false, mean = false;
    bool all() const { return cv && p999 && dark && mean; }
};
TargetCheck checkTarget(const BlockStats& method, const BlockStats& reference);

// The light-turn angle (degrees about +y, common parameter light.turn) at which the per-pixel correlation of
// D / D_smooth with the unturned frame falls to 0.5 (linear interpolation between steps growing 1.5x from
// 0.02 degrees; infinity when it never does within 20 degrees). `method` may be kReferenceMethodId.
double lifespanDegrees(OffscreenSession& session, const SurfaceImage& surface, const RenderRequest& request,
                       const std::string& method);

}  // namespace glimmer::facets
