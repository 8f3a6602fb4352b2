/* glimmer-method
name:      clamped_glints
title:     deliot2023 with a dynamic-range clamp (deliberately broken: loses energy)
citation:  test fixture of tests/user_method_test.cpp: Deliot & Belcour 2023 with D clamped to 4 D_smooth
resources: deliot2023
converge:  log_density=40
param: log_density = 16 in [0, 50]: natural log of the microfacet density per unit UV area
param: microfacet_roughness = 0.005 in [0.001, 1] log: R, ratio of micro- to macro-roughness
param: density_randomization = 2 in [0, 10]: std. deviation of the per-vertex log density
param: screen_space_scale = 1.5 in [0.1, 10]: grid cell size in pixels across the footprint's minor axis
param: normalization = vertex in {vertex, footprint}: count normalization (see deliot2023)
param: angular_grid = projected in {projected, lobe}: Eq. 14 cell width (see deliot2023)
param: gate = soft in {soft, hard}: binomial gate (see deliot2023)
*/
// A deliberately broken user method for the failing check-method test. Clamping D to a few times the smooth
// NDF (a "dynamic range" guard against fireflies) is harmless where the facets are dense, so the method still
// converges to smooth at log_density=40, but at glinty densities each glint is cut down and the area-averaged
// energy falls far below one: the white-furnace rule must fail, and only that one.
#define glintD deliot2023GlintD
#include "glints/deliot2023/deliot2023.glsl"
#undef glintD

float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) {
    return min(deliot2023GlintD(px, s, h, wi, wo), 4.0 * D_smooth(h, s.alpha, s.ndf));
}
