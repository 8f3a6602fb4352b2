/* glimmer-method
name: g
citation: c
param: gain = 1 in [0, 2]: a gain
param: e = a in {a, b}: m
map: gain = ln(2 density_per_uv^0.5 alpha^-1) - gain^2/2
converge: gain=2
*/
#include "common/brdf.glsl"
#include "a.bin"
float glintD() { return 1.0; }
