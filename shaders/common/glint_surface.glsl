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
    // LEAN mapping (Olano & Baker 2010): the normal map's filtered slope covariance Sigma_xx, Sigma_yy, Sigma_xy
    // in the tangent frame, from the G-buffer when the method asks for it (GlintMethod::slopeCovariance); else 0.
    vec3 slopeCovariance;
    // Screen-space derivatives (one pixel right, one pixel up) of the world position and of the world shading
    // normal, and the distance to the eye, when the method asks for them (GlintMethod::surfaceDerivatives,
    // GLINT_SURFACE_DERIVATIVES); else 0.
    vec3 dpdx, dpdy, dndx, dndy;
    float viewDistance;
};

// With GLINT_SURFACE_DERIVATIVES the lighting pass sets this before each glintD call: the distance to a point or
// spot light, 0 for a directional light (whose direction does not change across the screen).
float g_glintLightDistance = 0.0;

// The optional fields at their "not provided" values.
void clearGlintSurfaceExtras(inout GlintSurface s) {
    s.slopeCovariance = vec3(0.0);
    s.dpdx = s.dpdy = s.dndx = s.dndy = vec3(0.0);
    s.viewDistance = 0.0;
}

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
    clearGlintSurfaceExtras(s);
    return s;
}
