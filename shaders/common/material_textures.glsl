// Material texture lookups shared by the G-buffer and the forward (emissive, transparent) passes.
// Extreme texture footprints (issue 14, fuzz-hang-100226: a material uvScale of [65538, 2]; docs/cli.md).
// llvmpipe's anisotropic filter is an EWA scan over the texel bounding box of the footprint, which it derives
// from the coordinates of the 2x2 quad (explicit gradients are ignored) at the mip level of the minor axis, with
// no cap: its cost grows with the anisotropy and with footprints wider than the texture, and it runs
// even for samples a branch masks off. GPUs cap their filter at 16 samples. Quads whose footprint is wider than
// the texture or more anisotropic than kMaxFilteredAnisotropy therefore hand the filtered lookup a constant
// coordinate (a one-texel scan) and take a textureLod at the level of the major axis / 16 instead (the
// texture's mean, its 1x1 level, for footprints wider than it). Every other quad samples exactly as before.
const float kMaxFilteredAnisotropy = 256.0;
struct TextureFootprint { bool extreme; float major; };

TextureFootprint textureFootprint(vec2 uv) {
    // Coarse derivatives: one decision per 2x2 quad, so a quad never mixes real and constant coordinates.
    FootprintEllipse e = footprintEllipse(dFdxCoarse(uv), dFdyCoarse(uv));
    TextureFootprint f;
    f.extreme = !(e.major <= kMaxFilteredAnisotropy * e.minor) || !(e.major <= 1.0);   // NaN counts as extreme
    f.major = e.major;
    return f;
}

vec4 sampleTexture(sampler2D t, vec2 uv, TextureFootprint f) {
    vec4 filtered = texture(t, f.extreme ? vec2(0.5) : uv);
    ivec2 size = textureSize(t, 0);
    float lod = f.major <= 1.0 ? log2(max(f.major * float(max(size.x, size.y)) / 16.0, 1.0)) : 64.0;
    // The scan also runs for an explicit level above 0, over the quad's coordinate differences: a footprint wider
    // than the texture reads the 1x1 level at a constant coordinate.
    vec4 coarse = textureLod(t, f.extreme && f.major <= 1.0 ? uv : vec2(0.5), lod);
    return f.extreme ? coarse : filtered;
}
