// The smooth reference: the analytic NDF itself (no glints). Every glint method converges to this.
// Extended lights: D_smooth for every light, so an area light's factor is 1 (its smooth LTC specular).
struct GlintPixel { FootprintEllipse footprint; };

GlintPixel glintSetup(GlintSurface s) {
    GlintPixel px;
    px.footprint = footprintEllipse(s.duvdx, s.duvdy);
    return px;
}

float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) { return D_smooth(h, s.alpha, s.ndf); }

vec4 glintFootprintAOV(GlintPixel px, GlintSurface s) {
    float ratio = px.footprint.major / px.footprint.minor;
    return vec4(ratio, log2(px.footprint.minor), px.footprint.major, px.footprint.minor);
}

vec4 glintExtraAOV(GlintPixel px, GlintSurface s) { return vec4(0.0); }
