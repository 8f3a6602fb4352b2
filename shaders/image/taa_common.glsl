// Shared by the TAA resolve (taa_resolve.frag) and the TAA upsampling resolve (taa_upsample.frag): colour space
// and clipping of the history rectification (Salvi 2016), and the sharpened history fetch (Karis 2014).
vec3 rgbToYCoCg(vec3 c) {
    return vec3(dot(c, vec3(0.25, 0.5, 0.25)), dot(c, vec3(0.5, 0.0, -0.5)), dot(c, vec3(-0.25, 0.5, -0.25)));
}
vec3 yCoCgToRgb(vec3 c) { return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z); }

vec3 finiteOrZero(vec3 c) { return any(isnan(c)) || any(isinf(c)) ? vec3(0.0) : c; }

// Catmull-Rom history fetch with 5 bilinear taps (the 4x4 kernel without its corners, renormalised).
vec3 sampleHistoryCatmullRom(sampler2D history, vec2 uv, vec2 size) {
    vec2 position = uv * size;
    vec2 center1 = floor(position - 0.5) + 0.5;
    vec2 f = position - center1;
    vec2 w0 = f * (-0.5 + f * (1.0 - 0.5 * f));
    vec2 w1 = 1.0 + f * f * (-2.5 + 1.5 * f);
    vec2 w2 = f * (0.5 + f * (2.0 - 1.5 * f));
    vec2 w3 = f * f * (-0.5 + 0.5 * f);
    vec2 w12 = w1 + w2;
    vec2 p0 = (center1 - 1.0) / size, p3 = (center1 + 2.0) / size, p12 = (center1 + w2 / w12) / size;
    vec3 sum = textureLod(history, vec2(p12.x, p0.y), 0.0).rgb * (w12.x * w0.y) +
               textureLod(history, vec2(p0.x, p12.y), 0.0).rgb * (w0.x * w12.y) +
               textureLod(history, p12, 0.0).rgb * (w12.x * w12.y) +
               textureLod(history, vec2(p3.x, p12.y), 0.0).rgb * (w3.x * w12.y) +
               textureLod(history, vec2(p12.x, p3.y), 0.0).rgb * (w12.x * w3.y);
    float weight = w12.x * w0.y + w0.x * w12.y + w12.x * w12.y + w3.x * w12.y + w12.x * w3.y;
    return max(sum / weight, vec3(0.0));
}

// Moves `history` along the line to `center` until it is inside the box center +- extent (Salvi 2016).
vec3 clipToBox(vec3 history, vec3 center, vec3 extent) {
    vec3 offset = history - center;
    vec3 units = abs(offset / max(extent, vec3(1e-7)));
    float largest = max(units.x, max(units.y, units.z));
    return largest > 1.0 ? center + offset / largest : history;
}
