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

// A surface outside the lighting pass (probes and test kernels): frame columns tangent, bitangent, normal;
// material 0; position at the origin.
GlintSurface makeGlintSurface(vec2 uv, vec2 duvdx, vec2 duvdy, float alpha, int ndf, float densityScale, ivec2 pixel,
                              mat3 frame) {
    GlintSurface s;
    s.uv = uv;
    s.duvdx = duvdx;
    s.duvdy = duvdy;
    s.alpha = alpha;
    s.ndf = ndf;
    s.densityScale = densityScale;
    s.materialId = 0;
    s.pixel = pixel;
    s.t = frame[0];
    s.b = frame[1];
    s.n = frame[2];
    s.position = vec3(0.0);
    return s;
}
