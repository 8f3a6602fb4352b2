// What the lighting pass hands to a glint method for one pixel (see shaders/glints/README.md).

// A loop bound the compiler cannot fold (u_viewport.x, the frame's width, is never negative; common/frame.glsl):
// Mesa unrolls constant-bound loops, and llvmpipe then compiles a large unrolled body for seconds (the lighting
// program's first draw); loops with big bodies that run per light or per level keep their loop with this.
int glintLoopCount(int n) { return u_viewport.x >= 0 ? n : 0; }
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

// The light a glint method is evaluated for (shaders/glints/README.md "Extended lights"): the lighting pass sets it
// before each glintD (punctual and directional lights) and glintAreaFactor (area lights); elsewhere (probes, test
// kernels) it is a light of no size. Methods may ignore it.
struct GlintLight {
    bool area;             // an area light: glintAreaFactor; false: glintD
    float solidAngle;      // sr, seen from the point: the sun's disk, a point light's sphere of its radius (0: none),
                           // an area light's (exact for spheres, A |cos| / d^2 for rects and disks)
    float ndfIntegral;     // the integral over the light of D(h) / (4 |l.h|) dl (Kneiphof & Klein 2024, Sec. 4):
                           // area lights: the NDF-only term times the specular LTC's integral over the light (their
                           // default reading); punctual lights: D(h) solidAngle / (4 (l.h))
    float specular;        // area lights: the smooth specular lobe's LTC integral over the light (radiance / (L (f0 A + B)))
    // Area lights, for methods that integrate a lobe of their own over the light (lights/ltc.glsl): the light in
    // the pixel's LTC frame (lights/area_light.glsl AreaLightGeometry), the NDF-only LTC and its magnitude.
    int shape;
    vec3 centre, halfU, halfV;
    mat3 invNdfOnly;
    float ndfOnlyMagnitude;
};
GlintLight g_glintLight = GlintLight(false, 0.0, 0.0, 0.0, 0, vec3(0.0), vec3(0.0), vec3(0.0), mat3(1.0), 0.0);

// The environment as glints see it (Kneiphof & Klein 2025, "Real-time Image-based Lighting of Glints"): a few
// radiance levels and, along the pixel's reflected lobe, the fraction of the lobe that sees each level. The IBL
// mode hands it to a method that defines GLINT_ENVIRONMENT (glintEnvironmentFactor; README "Environment glints").
struct GlintEnvironment {
    int levels;            // K = 4 or 8 (level 0 is radiance 0); 0: no levels (no environment glints)
    float radiance[8];     // L_i, luminance (x env.intensity), log-spaced between the environment's extremes
    float weight[8];       // w_i: prefiltered indicator of level i at the lobe (they sum to 1)
    float ndfIntegral;     // the integral over the hemisphere of lights of D(h) / (4 |l.h|) (p_base x total NDF)
};
// The part of iblRadiance's result that is environment glints (the IBL mode sets it on glinty pixels): the lighting
// pass adds it to the glint part TAA keeps out of its neighbourhood clipping.
vec3 g_environmentGlintPart = vec3(0.0);
