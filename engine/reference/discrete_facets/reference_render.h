// `glimmer render --method reference` and the `reference` column of `render --compare`: the exact discrete-facet
// reference (facet_image.h) shown through the renderer's own pipeline. How:
//  1. the view is rendered with `smooth` once per AOV the reference reads (normal, tangent with the bitangent sign,
//     uv, duvdx, duvdy, depth, material), so it runs on any scene;
//  2. the CPU counts the facets of every glinty pixel for every light (and, with an environment, the facets'
//     reflection of the map, environment_glints.h);
//  3. the view is rendered with the method `reference` (shaders/glints/reference/reference.glsl), whose NDF reads
//     the CPU's D_est for the light being shaded, and whose pass adds the environment glints: shadows, Fresnel,
//     masking, tone mapping and everything else are the renderer's, as for every other method.
// The method is registered in the method table only by the commands that offer it (registerReferenceMethod); the
// renderer never names it, and nothing of it runs unless it is asked for.
#pragma once
#include <string>

#include "reference/discrete_facets/facet_image.h"
#include "offscreen/offscreen.h"

namespace glimmer::facets {

inline constexpr const char* kReferenceMethodId = "reference";

// Adds `reference` to the method table (once per process; later calls do nothing). Its parameters (--set
// reference.<name>=V): lobe (cone, gaussian), footprint (box, gaussian), seed, threads, env_samples.
void registerReferenceMethod();

// The reference's options from a request's `reference.*` parameters.
ReferenceOptions referenceOptions(const RenderSettings& settings);

// The G-buffer of `request`'s view as the reference reads it (smooth renders of the AOVs, same session).
SurfaceImage captureSurface(OffscreenSession& session, const RenderRequest& request);

// The whole reference render of `request` (its method is ignored), in `session`. Throws UsageError when the
// request cannot be rendered exactly (anti-aliasing or a render scale that moves the footprints).
RenderResult renderReference(OffscreenSession& session, const RenderRequest& request);

// One line naming the reference's parameters and the first glinty material's (the comparison grid's caption).
std::string referenceCaption(const Scene& scene, const RenderSettings& settings);

}  // namespace glimmer::facets
