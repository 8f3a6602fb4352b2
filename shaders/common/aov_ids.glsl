// Ids of the output channels (`--aov`, the window's debug views), shared by GLSL and C++ like bindings.glsl: the
// shaders get them through common/frame.glsl, the table of names in engine/render/aov.cpp includes this file as it
// is, so it holds #define lines and comments only. tests/aov_ids_test.cpp checks that every id has a name there.
#define VIEW_FINAL 0
#define VIEW_ALBEDO 1
#define VIEW_NORMAL 2
#define VIEW_DEPTH 3
#define VIEW_UV 4
#define VIEW_DUVDX 5
#define VIEW_DUVDY 6
#define VIEW_GLINT 7
#define VIEW_FOOTPRINT 8
#define VIEW_TANGENT 9
#define VIEW_ROUGHNESS_METALLIC 10
#define VIEW_EXTRA 11              // method-specific channel (glintscale, evaluation counters, ...)
#define VIEW_SHADOW 12             // visibility of the first light (shadow maps; 0 where the surface faces away)
#define VIEW_AO 13                 // ambient occlusion (shaders/ao/)
#define VIEW_CLEARCOAT 14          // KHR_materials_clearcoat: intensity, roughness, coat weight (common/clearcoat.glsl)
