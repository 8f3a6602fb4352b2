// aa=ssaa: renders the request at ssaa.factor x its size (aa=off) and box-filters the HDR radiance down; the PNG is
// the filtered radiance through the tone curve with the manual exposure (no bloom, no metering: a reference for
// anti-aliasing measurements, which compare radiance or this display image).
#pragma once
#include <functional>

#include "offscreen/offscreen.h"

namespace glimmer::image {

RenderResult supersampledRender(const RenderRequest& request,
                                const std::function<RenderResult(const RenderRequest&)>& renderOnce);

// Mean of each factor x factor block of an RGBA image (sizes: width * factor x height * factor in).
std::vector<float> boxDownsample(const std::vector<float>& rgba, int width, int height, int factor);

}  // namespace glimmer::image
