// Binding points and texture units, shared by GLSL and C++: the C++ side includes this file as it is
// (#include "common/bindings.glsl", the shaders folder is on the engine's include path), so it holds #define lines
// and comments only. Ranges: the renderer's own below 8, glint methods 8-15, IBL modes 16-23.

// Uniform blocks (std140) and shader storage buffers (std430); the two kinds have separate binding namespaces.
#define BINDING_FRAME 0              // uniform FrameBlock (common/frame.glsl; C++ FrameUniforms)
#define BINDING_LIGHTS 1             // storage LightBlock
#define BINDING_MATERIALS 2          // storage MaterialBlock
#define BINDING_METHOD_PARAMS 3      // uniform: the glint method's shared parameters (PS_<NAME>; P_<NAME> outside lighting)
#define BINDING_MATERIAL_METHOD_PARAMS 4  // storage: the method's parameters per material (P_<NAME> in lighting)
#define BINDING_IBL_PARAMS 5         // uniform: the IBL mode's parameters (IBL_<NAME>)
#define BINDING_ENVIRONMENT 7        // uniform EnvironmentBlock (common/ibl.glsl)
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
#define UNIT_ENV_SPECULAR 6          // samplerCubeArray: prefiltered environment (layer = NDF)
#define UNIT_ENV_BRDF_LUT 7          // sampler2D: split-sum table
#define UNIT_METHOD_FIRST 8          // glint methods: 8..15
#define UNIT_METHOD_LAST 15
#define UNIT_IBL_FIRST 16            // IBL modes: 16..23
#define UNIT_IBL_LAST 23
#define UNIT_ENV_SOURCE 24           // samplerCube: unfiltered environment with its box mip chain

// Texture units of the G-buffer pass (the material's textures, bound per draw by GpuScene).
#define UNIT_MATERIAL_BASE_COLOR 0
#define UNIT_MATERIAL_METALLIC_ROUGHNESS 1
#define UNIT_MATERIAL_NORMAL 2
#define UNIT_MATERIAL_OCCLUSION 3
#define UNIT_MATERIAL_GLINT_MASK 4

// Full-screen passes after lighting read their inputs from units 0.. in the order their shaders list them.
#define UNIT_TONEMAP_HDR 0
