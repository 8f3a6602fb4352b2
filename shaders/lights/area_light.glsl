// Rectangle, disk and sphere lights (engine/scene/scene.h LightType::Rect, Disk, Sphere) in the lighting pass: the
// light's geometry seen from the shaded point, its diffuse form factor and the LTC integrals of the specular lobe
// (lights/ltc.glsl). Radiance: every area light is a Lambertian emitter of radiance colour x colorIntensity.a
// (intensity / area on the CPU: render/gpu_scene.cpp), one-sided for rects and disks (towards cross(U, V)) unless
// two-sided. Needs common/frame.glsl (GpuLight) and lights/ltc.glsl.
const int LIGHT_RECT = 3;
const int LIGHT_DISK = 4;
const int LIGHT_SPHERE = 5;
const int AREA_SHAPE_RECT = 0;
const int AREA_SHAPE_ELLIPSE = 1;   // disks, and spheres as the disk of their silhouette

// The light in the pixel's LTC frame (rows t1, t2, n of LtcPixel.toFrame), relative to the point.
struct AreaLightGeometry {
    int shape;             // AREA_SHAPE_*
    vec3 centre, halfU, halfV;
    bool visible;          // false: a one-sided light seen from behind, or beyond its range
    float window;          // KHR_lights_punctual's range window on the distance to the centre (1 without a range)
    float solidAngle;      // sr (exact for spheres; A |cos| / d^2 for rects and disks, capped at 2 pi)
    vec3 towardCentre;     // world, unit
    float sinSigma2;       // spheres: sin^2 of the silhouette's half-angle
};

AreaLightGeometry areaLightGeometry(GpuLight light, vec3 position, mat3 toFrame) {
    AreaLightGeometry g;
    int type = int(light.vectorType.w + 0.5);
    vec3 c = light.vectorType.xyz - position;
    float d2 = max(dot(c, c), 1e-12);
    float d = sqrt(d2);
    g.towardCentre = c / d;
    vec3 U = light.areaU.xyz, V = light.areaV.xyz;
    g.visible = true;
    g.sinSigma2 = 0.0;
    if (type == LIGHT_SPHERE) {
        // The sphere's cone of directions is the cone through the disk facing the point at the centre's distance,
        // of radius d tan(sigma), sin(sigma) = r / d (clamped just inside the sphere).
        float sinSigma = min(light.areaV.w / d, 0.9995);
        g.sinSigma2 = sinSigma * sinSigma;
        float r = d * sinSigma * inversesqrt(1.0 - g.sinSigma2);
        vec3 t = abs(g.towardCentre.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
        t = normalize(cross(g.towardCentre, t));
        U = r * t;
        V = r * cross(g.towardCentre, t);
        g.shape = AREA_SHAPE_ELLIPSE;
        g.solidAngle = 2.0 * PI * (1.0 - sqrt(1.0 - g.sinSigma2));
    } else {
        g.shape = type == LIGHT_RECT ? AREA_SHAPE_RECT : AREA_SHAPE_ELLIPSE;
        vec3 normal = cross(U, V);
        float facing = dot(-c, normal);
        g.visible = light.areaU.w > 0.5 || facing > 0.0;
        float area = (type == LIGHT_RECT ? 4.0 : PI) * length(normal);
        g.solidAngle = min(area * abs(facing) / (max(length(normal), 1e-20) * d2 * d), 2.0 * PI);
    }
    float range = light.spotOffsetRange.y;
    g.window = 1.0;
    if (range > 0.0) {
        float r2 = d2 / (range * range);
        float w = clamp(1.0 - r2 * r2, 0.0, 1.0);
        g.window = w * w;
    }
    g.visible = g.visible && g.window > 0.0;
    g.centre = toFrame * c;
    g.halfU = toFrame * U;
    g.halfV = toFrame * V;
    return g;
}

// False when the light adds nothing at `position` (normal n; `coatN` a clear coat's normal, n when uncoated): beyond
// its range, a one-sided light seen from behind, or wholly below both horizons (every point of a rect below the
// tangent plane: dot(c, n) + |U.n| + |V.n| <= 0; of a disk: dot(c, n) + sqrt((U.n)^2 + (V.n)^2) <= 0; of a sphere:
// dot(c, n) + r <= 0). Both LTC integrals clip at the horizon, so such a light's diffuse and specular are exactly 0.
// Cheap enough to run for every light before the loop that pays for the integrals (lighting.frag).
bool areaLightReaches(GpuLight light, vec3 position, vec3 n, vec3 coatN) {
    vec3 c = light.vectorType.xyz - position;
    float range = light.spotOffsetRange.y;
    if (range > 0.0 && dot(c, c) >= range * range) return false;
    int type = int(light.vectorType.w + 0.5);
    vec3 U = light.areaU.xyz, V = light.areaV.xyz;
    if (type == LIGHT_SPHERE) return max(dot(c, n), dot(c, coatN)) + light.areaV.w > 0.0;
    if (!(light.areaU.w > 0.5 || dot(c, cross(U, V)) < 0.0)) return false;
    vec2 un = vec2(dot(U, n), dot(U, coatN)), vn = vec2(dot(V, n), dot(V, coatN));
    vec2 reach = type == LIGHT_RECT ? abs(un) + abs(vn) : sqrt(un * un + vn * vn);
    vec2 top = vec2(dot(c, n), dot(c, coatN)) + reach;
    return max(top.x, top.y) > 0.0;
}

// The clamped cosine's integral over the light mapped by invM (Heitz et al. 2016, Eq. 7): the LTC of invM
// integrated over the light. invM = identity: the diffuse form factor.
float ltcAreaIntegral(int shape, vec3 centre, vec3 halfU, vec3 halfV, mat3 invM) {
    vec3 C = invM * centre, U = invM * halfU, V = invM * halfV;
    if (shape == AREA_SHAPE_RECT) return ltcQuadCosine(C - U - V, C + U - V, C + U + V, C - U + V);
    return ltcEllipseCosine(C, U, V);
}
