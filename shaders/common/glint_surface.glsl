// What the lighting pass hands to a glint method for one pixel (see shaders/glints/README.md).
struct GlintSurface {
    vec2 uv;            // UV0, 32-bit
    vec2 duvdx;         // screen-space derivatives from the G-buffer pass
    vec2 duvdy;
    float alpha;        // NDF roughness
    int ndf;            // NDF_GGX or NDF_BECKMANN
    float densityScale; // per-material density scale x glint mask texture
    int materialId;
    ivec2 pixel;
    vec3 n, t, b;       // world-space shading frame
    vec3 position;      // world-space position (UV-free / triplanar methods)
};
