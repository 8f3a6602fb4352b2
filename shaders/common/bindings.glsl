// Binding points and texture units, shared by GLSL and C++: the C++ side includes this file as it is
// (#include "common/bindings.glsl", the shaders folder is on the engine's include path), so it holds #define lines
// and comments only. Ranges: the renderer's own below 8, glint methods 8-15, IBL modes 16-23.

// Uniform blocks (std140) and shader storage buffers (std430); the two kinds have separate binding namespaces.
#define BINDING_FRAME 0              // uniform FrameBlock (common/frame.glsl; C++ FrameUniforms)
#define BINDING_LIGHTS 1             // storage LightBlock
#define BINDING_MATERIALS 2          // storage MaterialBlock
#define BINDING_METHOD_PARAMS 3      // uniform: the glint method's shared parameters (PS_<NAME>; P_<NAME> outside lighting)
#define BINDING_MATERIAL_METHOD_PARAMS 3  // storage (not the uniform 3 above): the method's parameters per material (P_<NAME> in lighting)
#define BINDING_EXPOSURE_HISTOGRAM 4 // storage: log2-luminance histogram (image/exposure_common.glsl)
#define BINDING_SHADOWS 4            // uniform ShadowBlock (shadows/shadows.glsl; C++ render/shadows/shadow_maps.cpp); storage 4 is the histogram
#define BINDING_IBL_PARAMS 5         // uniform: the IBL mode's parameters (IBL_<NAME>)
#define BINDING_METHOD_OUTPUT 5      // storage (not the uniform 5 above): counters of what the glint method produced (render/frame/method_output_check.h)
#define BINDING_EXPOSURE_STATE 6     // storage: metered and target EV (exposure pass -> tone-mapping pass)
#define BINDING_PROBES 6             // uniform (not the storage 6 above) ProbeBlock (environment/prefiltered_lookup.glsl; C++ ProbeUniforms, render/probes/reflection_probes.h)
#define BINDING_ENVIRONMENT 7        // uniform EnvironmentBlock (environment/prefiltered_lookup.glsl)
#define BINDING_ENV_GLINTS 7         // storage (not the uniform 7 above): environment glint levels (environment/glint_levels.glsl)
#define BINDING_METHOD_FIRST 8       // glint methods: 8..15
#define BINDING_METHOD_LAST 15
#define BINDING_IBL_FIRST 16         // IBL modes: 16..23
#define BINDING_IBL_LAST 23

// Texture units of the lighting pass.
#define UNIT_GBUFFER_FIRST 0         // G-buffer colour targets 0..4 (layout in gbuffer.frag)
#define UNIT_GBUFFER_UV_DUVDX 0
#define UNIT_GBUFFER_DUVDY_MATERIAL 1
#define UNIT_GBUFFER_NORMAL_ALPHA 2
#define UNIT_GBUFFER_TANGENT_METALLIC 3
#define UNIT_GBUFFER_BASE_COLOR_MASK 4
#define UNIT_GBUFFER_DEPTH 5         // reversed-Z depth
#define UNIT_GBUFFER_CLEARCOAT 30    // G-buffer colour target 5: coat normal (octahedral), coat factor, coat roughness
// G-buffer colour target 6 (slope covariance of the LEAN-filtered normal map), lighting pass only, for methods that
// declare GlintMethod::slopeCovariance: on the last method unit, which such methods leave free.
#define UNIT_GBUFFER_SLOPE_COVARIANCE 15
#define UNIT_ENV_SPECULAR 6          // samplerCubeArray: the unfiltered environment, layer = NDF (rung 0 of the ladder)
#define UNIT_ENV_BRDF_LUT 7          // sampler2D: split-sum table
#define UNIT_METHOD_FIRST 8          // glint methods: 8..15
#define UNIT_METHOD_LAST 15
#define UNIT_IBL_FIRST 16            // IBL modes: 16..23
#define UNIT_IBL_LAST 23
#define UNIT_ENV_SOURCE 24           // samplerCube: unfiltered environment with its box mip chain
#define UNIT_ENV_SPECULAR_FINE 25    // samplerCubeArray: the prefiltered environment's sublevels (environment/environment.h)
#define UNIT_PROBE_SPECULAR 26       // samplerCubeArray: reflection probes, layer = 2 * probe + NDF; level 0 unfiltered
#define UNIT_AMBIENT_OCCLUSION 27    // sampler2D: rgb factor on the environment / ambient term, a visibility (ao/)
#define UNIT_SHADOW_SUN 28           // sampler2DArrayShadow: sun cascades (render/shadows/shadow_maps.h)
#define UNIT_SHADOW_LOCAL 29         // sampler2DArrayShadow: point-light cube faces and spot-light views
#define UNIT_SHADOW_MASK 31          // sampler2DArray: shadowed lights' visibility, 4 a layer (passes/shadow_mask_pass.h)
// Units 32 and up (GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS is 192 on llvmpipe; a stage still reads at most 32 samplers).
#define UNIT_LTC_TABLE 32            // sampler2DArray: the area lights' LTC tables (render/lights/ltc_texture.h)
#define UNIT_SHADOW_LOCAL_DEPTH 33   // sampler2DArray: the local-light depth array without compare (soft shadows)
#define UNIT_ENV_GLINT_WEIGHTS 34    // samplerCubeArray: the environment's prefiltered glint-level weights (KK25)
#define UNIT_PROBE_GLINT_WEIGHTS 35  // samplerCubeArray: the reflection probes' ones
#define UNIT_GLINT_LEVEL_SOURCE 0    // compute passes of engine/environment/environment_glints.cpp: their source

// Texture units of the G-buffer pass (the material's textures, bound per draw by GpuScene).
#define UNIT_MATERIAL_BASE_COLOR 0
#define UNIT_MATERIAL_METALLIC_ROUGHNESS 1
#define UNIT_MATERIAL_NORMAL 2
#define UNIT_MATERIAL_OCCLUSION 3
#define UNIT_MATERIAL_GLINT_MASK 4
#define UNIT_MATERIAL_EMISSIVE 5        // emissive and transparent passes only (unit 5 is the G-buffer depth elsewhere)
// KHR_materials_clearcoat, G-buffer pass only: units 6-8 are the environment's and the method's in the passes that
// follow, and the lighting pass rebinds those each frame (forward passes never bind these three).
#define UNIT_MATERIAL_CLEARCOAT 6
#define UNIT_MATERIAL_CLEARCOAT_ROUGHNESS 7
#define UNIT_MATERIAL_CLEARCOAT_NORMAL 8
// The same three textures in the forward passes (emissive, transparent), on method units: no forward shader reads a
// method's resources, and the lighting pass rebinds those every frame.
#define UNIT_FORWARD_CLEARCOAT 12
#define UNIT_FORWARD_CLEARCOAT_ROUGHNESS 13
#define UNIT_FORWARD_CLEARCOAT_NORMAL 14
// LEAN maps (Olano & Baker 2010) of the normal texture, G-buffer pass only, for glint methods that filter normal
// maps (GlintMethod::slopeCovariance; render/gpu_scene.h): mean slope and second moments.
#define UNIT_MATERIAL_LEAN_MOMENTS 9   // RGBA16F: E[m_x], E[m_y], E[m_x^2], E[m_y^2]
#define UNIT_MATERIAL_LEAN_CROSS 10    // R16F: E[m_x m_y]

// Ambient-occlusion passes (shaders/ao/: gtao.frag, ao_resolve.frag), before lighting.
#define UNIT_AO_DEPTH 0
#define UNIT_AO_NORMAL 1
#define UNIT_AO_RAW 2                // the GTAO pass's visibility, before denoising
#define UNIT_AO_BASE_COLOR 3
#define UNIT_AO_TANGENT_METALLIC 4
#define UNIT_AO_SKY 5                // sampler3D: baked sky-visibility probes

// Full-screen passes after lighting read their inputs from units 0.. in the order their shaders list them.
#define UNIT_TONEMAP_HDR 0
#define UNIT_TONEMAP_BLOOM 1         // half-size bloom sum (bloom pass), bilinear
#define UNIT_TAA_CURRENT 0           // this frame's HDR radiance
#define UNIT_TAA_GLINT_PART 1        // the glint part of it (lighting pass, location 3)
#define UNIT_TAA_DEPTH 2
#define UNIT_TAA_HISTORY_BASE 3      // previous resolve, non-glint part (+ sample count in a)
#define UNIT_TAA_HISTORY_GLINT 4     // previous resolve, glint part
#define UNIT_BLOOM_SOURCE 0
#define UNIT_EXPOSURE_HDR 0
#define UNIT_UPSCALE_SOURCE 0        // the window's Catmull-Rom upscale (image/upscale.frag): the display image

// wang2020's post pass (glints/wang2020/wang2020_glint_*.frag, engine/glints/wang2020/wang2020_post_pass.cpp).
#define UNIT_GLINT_ENVIRONMENT 0     // rgb: environment glints, a: visibility (the lighting pass's glint target)
#define UNIT_GLINT_LIGHTS 1          // rgb: light glints, a: 1 on glinty pixels
#define UNIT_GLINT_OCCLUSION_SUMS 2  // the occlusion blur's first pass (along x), read by its second
#define UNIT_OCCLUDED_GLINT 0        // the glint blur's input: occluded glints

// Environment precompute (engine/environment/, shaders/environment/*.comp): each compute program reads its input
// at texture unit 0 (and 1) and writes image unit 0 (and 1); image units are a namespace of their own.
#define UNIT_ENV_INPUT 0             // equirect_to_cube: the map; resample_cube: the source array; radiance_centroid:
                                     // the source cube's faces as layers
#define UNIT_ENV_WEIGHTED 0          // prefilter: radiance x solid angle with its box mips (radiance_centroid.comp)
#define UNIT_ENV_CENTROID 1          // prefilter: luminance-weighted direction and solid angle with its box mips
#define IMAGE_ENV_OUTPUT 0           // what brdf_lut, procedural_sky, equirect_to_cube, resample_cube, prefilter write
#define IMAGE_ENV_WEIGHTED 0         // radiance_centroid's two outputs: level 0 of the prefilter's sum chains
#define IMAGE_ENV_CENTROID 1
#define IMAGE_PYRAMID_SOURCE 0       // environment/ibl/cube_pyramid.comp: level m - 1 of the cube (read)
#define IMAGE_PYRAMID_TARGET 1       // ... and level m (written)

// Compute rigs of the tests that write per-sample results for the CPU to read (environment/ibl/ibl_estimator_test.glsl,
// glints/kemppinen2025/kemppinen2025_sampling_test.glsl): storage buffers at the start of the method range, which the
// methods these rigs run (kemppinen2025, deliot2023, smooth) leave free.
#define BINDING_RIG_OUTPUT BINDING_METHOD_FIRST
#define BINDING_RIG_OUTPUT_2 (BINDING_METHOD_FIRST + 1)

// Uniform locations of the UI overlay (ui/ui.vert, ui/ui.frag; engine/ui/ui_renderer.cpp).
#define LOCATION_UI_SCREEN_SIZE 0
#define LOCATION_UI_GLYPH_ROWS 1
