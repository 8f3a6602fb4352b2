#include "scene/atrium.h"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

#include "scene/mesh_builder.h"
#include "scene/procedural_textures.h"
#include "scene/uv_transform.h"

namespace glimmer {
namespace {

using namespace atrium;
const glm::vec3 kUp(0.0f, 1.0f, 0.0f);
constexpr float kPi = glm::pi<float>();

// Heights of one storey of the arcade.
struct Storey {
    float base;          // floor level
    float plinthTop;     // column plinth
    float capitalBottom; // top of the shaft
    float springing;     // top of the capital, where the arches spring
    float top;           // top of the arcade wall (next floor or the roof)
};
constexpr Storey kGround{0.0f, 0.35f, 3.0f, 3.3f, kUpperFloor};
constexpr Storey kUpper{kUpperFloor, 5.62f, 7.55f, 7.85f, kRoof};
constexpr float kColumnRadius = 0.25f;
constexpr float kCapitalHalf = 0.35f;
constexpr float kSlabThickness = 0.4f;   // between the aisle ceiling and the gallery floor
constexpr float kRoofThickness = 0.35f;
constexpr float kCornice = 0.25f;        // roof overhang into the court

// One side of the court: points are start + a * along + y * up + d * inward, with a along the column line
// (0 .. length), d across it (positive towards the court).
struct Side {
    glm::vec3 start;
    glm::vec3 along;
    glm::vec3 inward;
    float length;
    int bays;
    bool longSide;
    glm::vec3 at(float a, float y, float d) const { return start + a * along + y * kUp + d * inward; }
    // UVs on vertical faces of this side: u = a, v = y (continuous along the whole side).
    UvFrame wallFrame() const { return {start, along, kUp}; }
};

std::vector<Side> courtSides() {
    const float lx = 2.0f * kCourtHalfX, lz = 2.0f * kCourtHalfZ;
    // Counter-clockwise seen from above, each starting at its own corner column.
    return {
        {{-kCourtHalfX, 0, -kCourtHalfZ}, {1, 0, 0}, {0, 0, 1}, lx, kLongBays, true},    // north (z < 0)
        {{kCourtHalfX, 0, -kCourtHalfZ}, {0, 0, 1}, {-1, 0, 0}, lz, kShortBays, false},  // east (x > 0)
        {{kCourtHalfX, 0, kCourtHalfZ}, {-1, 0, 0}, {0, 0, -1}, lx, kLongBays, true},    // south (z > 0)
        {{-kCourtHalfX, 0, kCourtHalfZ}, {0, 0, -1}, {1, 0, 0}, lz, kShortBays, false},  // west (x < 0)
    };
}

// An axis-aligned box given in a side's (a, y, d) coordinates.
void sideBox(MeshBuilder& b, const Side& side, float a0, float a1, float y0, float y1, float d0, float d1,
             const std::vector<std::string>& skip = {}) {
    glm::vec3 p = side.at(a0, y0, d0), q = side.at(a1, y1, d1);
    b.box(glm::min(p, q), glm::max(p, q), glm::vec3(0.0f), skip);
}

// The wall above one storey's columns: per bay a rectangle [a, a + bay] x [springing, top] minus the half disc
// of the arch, on the court face and the aisle face, plus the arch soffit between them.
void arcadeWall(MeshBuilder& walls, MeshBuilder& stone, const Side& side, const Storey& storey) {
    const int archSegments = 24;
    const float half = 0.5f * kBay, height = storey.top - storey.springing;
    const float cornerAngle = std::atan2(height, half);
    std::vector<float> angles;
    for (int k = 0; k <= archSegments; ++k) angles.push_back(kPi * (1.0f - float(k) / archSegments));
    angles.push_back(kPi - cornerAngle);
    angles.push_back(cornerAngle);
    std::sort(angles.begin(), angles.end(), std::greater<float>());
    auto rim = [&](float centre, float angle) {   // (a, y) on the outer rectangle along the ray from the arch centre
        float c = std::cos(angle), s = std::sin(angle);
        float t = std::min(std::abs(c) > 1e-6f ? half / std::abs(c) : 1e30f, s > 1e-6f ? height / s : 1e30f);
        return glm::vec2(centre + t * c, storey.springing + t * s);
    };
    auto arch = [&](float centre, float angle) {
        return glm::vec2(centre + kArchRadius * std::cos(angle), storey.springing + kArchRadius * std::sin(angle));
    };
    for (int j = 0; j < side.bays; ++j) {
        float centre = (float(j) + 0.5f) * kBay;
        for (float d : {0.5f * kWall, -0.5f * kWall}) {
            glm::vec3 normal = d > 0 ? side.inward : -side.inward;
            for (size_t k = 0; k + 1 < angles.size(); ++k) {
                glm::vec2 p0 = arch(centre, angles[k]), p1 = arch(centre, angles[k + 1]);
                glm::vec2 q0 = rim(centre, angles[k]), q1 = rim(centre, angles[k + 1]);
                walls.quad(side.at(p0.x, p0.y, d), side.at(p1.x, p1.y, d), side.at(q1.x, q1.y, d), side.at(q0.x, q0.y, d),
                           normal, side.wallFrame());
            }
        }
        // Soffit: u = arc length along the intrados, v = depth across the wall.
        for (int k = 0; k < archSegments; ++k) {
            float t0 = kPi * float(k) / archSegments, t1 = kPi * float(k + 1) / archSegments;
            glm::vec2 p0 = arch(centre, t0), p1 = arch(centre, t1);
            float tm = 0.5f * (t0 + t1);
            glm::vec3 normal = -(std::cos(tm) * side.along + std::sin(tm) * kUp);
            uint32_t a = stone.vertex(side.at(p0.x, p0.y, -0.5f * kWall), normal, {kArchRadius * t0, -0.5f * kWall});
            uint32_t b = stone.vertex(side.at(p1.x, p1.y, -0.5f * kWall), normal, {kArchRadius * t1, -0.5f * kWall});
            uint32_t c = stone.vertex(side.at(p1.x, p1.y, 0.5f * kWall), normal, {kArchRadius * t1, 0.5f * kWall});
            uint32_t e = stone.vertex(side.at(p0.x, p0.y, 0.5f * kWall), normal, {kArchRadius * t0, 0.5f * kWall});
            stone.triangle(a, b, c);
            stone.triangle(a, c, e);
        }
    }
    // Wall ends past the corner columns (closing the corners) on both faces.
    for (auto [a0, a1] : {std::pair{-0.5f * kWall, 0.0f}, std::pair{side.length, side.length + 0.5f * kWall}})
        for (float d : {0.5f * kWall, -0.5f * kWall})
            walls.quad(side.at(a0, storey.springing, d), side.at(a1, storey.springing, d), side.at(a1, storey.top, d),
                       side.at(a0, storey.top, d), d > 0 ? side.inward : -side.inward, side.wallFrame());
}

void columns(MeshBuilder& stone, const Side& side, const Storey& storey) {
    for (int j = 0; j < side.bays; ++j) {   // the column at a = length belongs to the next side
        glm::vec3 c = side.at(float(j) * kBay, storey.base, 0.0f);
        glm::vec3 plinthHalf(kCapitalHalf, 0, kCapitalHalf);
        stone.box(c - plinthHalf, c + plinthHalf + glm::vec3(0, storey.plinthTop - storey.base, 0), glm::vec3(0.0f), {"-y"});
        stone.cylinder(c + glm::vec3(0, storey.plinthTop - storey.base, 0), kColumnRadius,
                       storey.capitalBottom - storey.plinthTop, 20, -side.inward);
        glm::vec3 capitalLo = c + glm::vec3(-kCapitalHalf, storey.capitalBottom - storey.base, -kCapitalHalf);
        glm::vec3 capitalHi = c + glm::vec3(kCapitalHalf, storey.springing - storey.base, kCapitalHalf);
        stone.box(capitalLo, capitalHi, glm::vec3(0.0f));
    }
}

// Slabs, roof, outer walls and the walkway on top of the ground arcade. Long sides own the corner squares.
void aisle(MeshBuilder& walls, MeshBuilder& stone, MeshBuilder& floor, const Side& side) {
    const float w = 0.5f * kWall;
    float a0 = side.longSide ? -kAisle : -w, a1 = side.longSide ? side.length + kAisle : side.length + w;
    // Gallery floor slab: its top is tiled floor, the rest stone.
    sideBox(stone, side, a0, a1, kUpperFloor - kSlabThickness, kUpperFloor, -kAisle, -w, {"+y"});
    glm::vec3 p = side.at(a0, kUpperFloor, -kAisle), q = side.at(a1, kUpperFloor, -w);
    glm::vec3 lo = glm::min(p, q), hi = glm::max(p, q);
    floor.quad({lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}, kUp, {});
    // Walkway on the arcade wall between the upper columns.
    float b0 = side.longSide ? -w : w, b1 = side.longSide ? side.length + w : side.length - w;
    sideBox(stone, side, b0, b1, kUpperFloor - 0.001f, kUpperFloor, -w, w, {"-y", "+z", "-z", "+x", "-x"});
    // Roof slab with a cornice over the court.
    float r0 = side.longSide ? -kAisle - 0.3f : w + kCornice, r1 = side.longSide ? side.length + kAisle + 0.3f : side.length - w - kCornice;
    sideBox(stone, side, r0, r1, kRoof, kRoof + kRoofThickness, -kAisle - 0.3f, w + kCornice);
    // Outer wall of the aisle, seen from inside.
    float o0 = -kAisle, o1 = side.length + kAisle;
    walls.quad(side.at(o0, 0, -kAisle), side.at(o1, 0, -kAisle), side.at(o1, kRoof, -kAisle), side.at(o0, kRoof, -kAisle),
               side.inward, side.wallFrame());
}

// Low balustrade between the upper columns.
void balustrade(MeshBuilder& stone, const Side& side) {
    for (int j = 0; j < side.bays; ++j) {
        float a0 = float(j) * kBay + kCapitalHalf, a1 = float(j + 1) * kBay - kCapitalHalf;
        sideBox(stone, side, a0, a1, kUpperFloor, kUpperFloor + 0.9f, -0.14f, 0.14f, {"-y"});
    }
}

// A drape hanging in front of the upper arcade of one bay, with vertical folds deepening downwards and a
// lower edge that sags in the middle. UVs are arc lengths on the cloth.
void drape(MeshBuilder& cloth, const Side& side, int bay, float phase) {
    const float width = 2.0f, top = 7.7f, length = 2.9f, period = 0.32f;
    float centre = (float(bay) + 0.5f) * kBay;
    cloth.grid(64, 28, [&](float s, float t) {
        float a = centre - 0.5f * width + s * width;
        float y = top - t * (length + 0.12f * std::sin(kPi * s));
        float depth = (0.02f + 0.035f * t) * std::sin(2.0f * kPi * s * width / period + phase);
        return side.at(a, y, 0.5f * kWall + 0.2f + depth + 0.08f * t);
    });
}

// Snow patch: an irregular blob just above the floor, UVs = world (x, z) so it continues the floor's metric.
void snowPatch(MeshBuilder& snow, glm::vec2 centre, glm::vec2 radii, float seed) {
    const int rings = 6, segments = 64;
    const float height = 0.004f;
    UvFrame frame;
    uint32_t middle = snow.vertex({centre.x, height, centre.y}, kUp, {centre.x, centre.y});
    std::vector<uint32_t> previous;
    for (int r = 1; r <= rings; ++r) {
        std::vector<uint32_t> ring;
        for (int s = 0; s < segments; ++s) {
            float phi = 2.0f * kPi * float(s) / segments;
            float wobble = 1.0f + 0.2f * std::sin(3.0f * phi + seed) + 0.1f * std::sin(5.0f * phi + 2.1f * seed) +
                           0.05f * std::sin(11.0f * phi + 3.7f * seed);
            float k = float(r) / rings * wobble;
            glm::vec3 p(centre.x + radii.x * k * std::cos(phi), height, centre.y + radii.y * k * std::sin(phi));
            ring.push_back(snow.vertex(p, kUp, frame.at(p)));
        }
        for (int s = 0; s < segments; ++s) {
            int n = (s + 1) % segments;
            if (r == 1) {
                snow.triangle(middle, ring[size_t(s)], ring[size_t(n)]);
            } else {
                snow.triangle(previous[size_t(s)], ring[size_t(s)], ring[size_t(n)]);
                snow.triangle(previous[size_t(s)], ring[size_t(n)], previous[size_t(n)]);
            }
        }
        previous = ring;
    }
}

// A lion-head-like relief (mane of radial locks, face, brow, eyes, muzzle, nose, mouth, ears) as a height
// field over a square plaque; heights in metres along the plaque normal.
float lionRelief(float x, float y) {
    float r = std::sqrt(x * x + y * y), phi = std::atan2(y, x);
    auto bump = [](float v, float lo, float hi) {
        float t = std::clamp((v - lo) / (hi - lo), 0.0f, 1.0f);
        return std::sin(kPi * t);
    };
    float mane = 0.055f * bump(r, 0.22f, 0.6f) * (0.65f + 0.35f * std::cos(18.0f * phi + 14.0f * r));
    float faceShape = 1.0f - (x / 0.27f) * (x / 0.27f) - ((y + 0.02f) / 0.32f) * ((y + 0.02f) / 0.32f);
    float face = faceShape > 0.0f ? 0.09f * std::sqrt(faceShape) : 0.0f;
    float h = std::max(mane, face);
    auto g = [](float dx, float dy, float s) { return std::exp(-(dx * dx + dy * dy) / s); };
    h += 0.022f * std::exp(-((y - 0.1f) * (y - 0.1f)) / 0.0009f) * g(x, 0, 0.03f);   // brow
    h -= 0.03f * (g(x - 0.1f, y - 0.05f, 0.0012f) + g(x + 0.1f, y - 0.05f, 0.0012f));  // eyes
    h += 0.05f * std::exp(-(x * x / 0.012f + (y + 0.13f) * (y + 0.13f) / 0.008f));     // muzzle
    h += 0.03f * g(x, y + 0.04f, 0.002f);                                              // nose
    h -= 0.025f * std::exp(-((y + 0.21f) * (y + 0.21f)) / 0.0006f) * g(x, 0, 0.02f);  // mouth
    h += 0.04f * (g(std::abs(x) - 0.24f, y - 0.27f, 0.003f));                         // ears
    float border = std::max(std::abs(x), std::abs(y));
    float fade = std::clamp((0.64f - border) / 0.06f, 0.0f, 1.0f);
    return std::max(h, 0.0f) * fade + 0.012f * fade;
}

Material material(const std::string& name, glm::vec3 colour, float alpha, float metallic, bool glinty) {
    Material m;
    m.name = name;
    m.baseColor = glm::vec4(colour, 1.0f);
    m.alpha = alpha;
    m.metallic = metallic;
    m.glinty = glinty;
    return m;
}

}  // namespace

Scene makeAtriumScene() {
    Scene scene;
    scene.name = "atrium";
    scene.skyColor = {0.32f, 0.42f, 0.56f};

    // Textures cover 2 m of surface (uvTransform scales metre UVs by 1/2); 512 texels: 3.9 mm per texel.
    const float texturePeriod = 2.0f;
    scene.textures.push_back(makeAshlarTexture(512, texturePeriod));
    scene.textures.push_back(makeStoneTexture(512, texturePeriod));
    scene.textures.push_back(makeFloorTileTexture(512, texturePeriod, 0.5f));

    enum : uint32_t { Ashlar, Stone, FloorTiles, Snow, CarPaintRed, CarPaintBlue, DrapeRed, DrapeBlue, DrapeGreen,
                      Bronze, Terracotta, MaterialCount };
    scene.materials.resize(MaterialCount);
    scene.materials[Ashlar] = material("ashlar", glm::vec3(1.0f), 0.55f, 0.0f, false);
    scene.materials[Ashlar].baseColorTexture = 0;
    scene.materials[Stone] = material("stone", glm::vec3(1.0f), 0.45f, 0.0f, false);
    scene.materials[Stone].baseColorTexture = 1;
    scene.materials[FloorTiles] = material("floor_tiles", glm::vec3(1.0f), 0.25f, 0.0f, false);
    scene.materials[FloorTiles].baseColorTexture = 2;
    for (uint32_t m : {Ashlar, Stone, FloorTiles}) scene.materials[m].uvTransform = uvTransformMatrix(glm::vec2(0.0f), 0.0f, glm::vec2(1.0f / texturePeriod));
    scene.materials[Snow] = material("snow", {0.9f, 0.92f, 0.95f}, 0.3f, 0.3f, true);
    scene.materials[CarPaintRed] = material("car_paint_red", {0.55f, 0.03f, 0.03f}, 0.2f, 0.8f, true);
    scene.materials[CarPaintBlue] = material("car_paint_blue", {0.05f, 0.15f, 0.6f}, 0.2f, 0.8f, true);
    scene.materials[DrapeRed] = material("drape_red", {0.5f, 0.05f, 0.06f}, 0.4f, 0.35f, true);
    scene.materials[DrapeBlue] = material("drape_blue", {0.06f, 0.12f, 0.45f}, 0.4f, 0.35f, true);
    scene.materials[DrapeGreen] = material("drape_green", {0.08f, 0.35f, 0.12f}, 0.4f, 0.35f, true);
    scene.materials[Bronze] = material("bronze", {0.72f, 0.45f, 0.2f}, 0.3f, 1.0f, false);
    scene.materials[Terracotta] = material("terracotta", {0.55f, 0.25f, 0.13f}, 0.6f, 0.0f, false);
    // Back faces culled where they can never be seen: the floor and snow lie on solid ground, the relief sits on
    // the stele, the blue car paint covers only closed solids (an egg, the sphere). Two-sided: the drapes (thin
    // cloth), the vases (open lathes whose inside shows from above), the red car paint they share with an egg, and
    // the masonry (ashlar, stone): culling it changed 35 pixels of the court golden image, lines along edges of the
    // upper arcade where a back face filled a crack between two solids (not investigated further; see
    // docs/performance.md).
    for (uint32_t m : {FloorTiles, Snow, CarPaintBlue, Bronze}) scene.materials[m].doubleSided = false;

    MeshBuilder floor("floor"), walls("walls"), stone("stonework"), snow("snow");
    MeshBuilder drapes[3] = {MeshBuilder("drapes_red"), MeshBuilder("drapes_blue"), MeshBuilder("drapes_green")};

    // Ground floor of court and aisles in 1 m cells (UV = world x, z).
    const float fx = kCourtHalfX + kAisle, fz = kCourtHalfZ + kAisle;
    for (float x = -fx; x < fx - 1e-3f; x += 1.0f)
        for (float z = -fz; z < fz - 1e-3f; z += 1.0f) {
            float x1 = std::min(x + 1.0f, fx), z1 = std::min(z + 1.0f, fz);
            floor.quad({x, 0, z}, {x1, 0, z}, {x1, 0, z1}, {x, 0, z1}, kUp, {});
        }

    std::vector<Side> sides = courtSides();
    int drapeIndex = 0;
    for (const Side& side : sides) {
        for (const Storey& storey : {kGround, kUpper}) {
            columns(stone, side, storey);
            arcadeWall(walls, stone, side, storey);
        }
        aisle(walls, stone, floor, side);
        balustrade(stone, side);
        if (side.longSide)
            for (int bay : {1, 3, 4, 6}) {
                drape(drapes[drapeIndex % 3], side, bay, 0.7f * float(drapeIndex));
                ++drapeIndex;
            }
    }

    // Snow on the court floor: a long patch in front of the grazing camera and a few smaller ones.
    snowPatch(snow, {1.5f, 0.8f}, {5.0f, 2.0f}, 0.0f);
    snowPatch(snow, {-8.0f, -2.6f}, {2.0f, 1.3f}, 1.3f);
    snowPatch(snow, {7.8f, 2.9f}, {1.8f, 1.1f}, 2.9f);
    snowPatch(snow, {-3.5f, 3.3f}, {1.6f, 0.8f}, 4.4f);

    // Plinths (stone): two for the car-paint eggs, four small ones for vases, a round one for the sphere.
    const glm::vec2 eggSpots[2] = {{-5.5f, -2.1f}, {-5.5f, 2.1f}};
    for (glm::vec2 e : eggSpots) stone.box({e.x - 0.45f, 0.0f, e.y - 0.45f}, {e.x + 0.45f, 1.0f, e.y + 0.45f}, {0, 0, 0}, {"-y"});
    const glm::vec2 vaseSpots[4] = {{-10.2f, -3.0f}, {10.2f, -3.0f}, {10.2f, 3.0f}, {-10.2f, 3.0f}};
    for (glm::vec2 v : vaseSpots) stone.box({v.x - 0.35f, 0.0f, v.y - 0.35f}, {v.x + 0.35f, 0.5f, v.y + 0.35f}, {0, 0, 0}, {"-y"});
    const glm::vec3 sphereCentre(4.5f, 1.7f, -2.3f);
    stone.cylinder({sphereCentre.x, 0.0f, sphereCentre.z}, 0.45f, 1.0f, 32, {0, 0, -1});
    stone.quad({sphereCentre.x - 0.45f, 1.0f, sphereCentre.z - 0.45f}, {sphereCentre.x + 0.45f, 1.0f, sphereCentre.z - 0.45f},
               {sphereCentre.x + 0.45f, 1.0f, sphereCentre.z + 0.45f}, {sphereCentre.x - 0.45f, 1.0f, sphereCentre.z + 0.45f}, kUp, {});

    // Stele with the lion relief and a basin at the west end of the court, facing +x.
    const float steleFace = -kCourtHalfX + 1.5f;
    stone.box({steleFace - 0.45f, 0.0f, -0.95f}, {steleFace, 2.9f, 0.95f}, {0, 0, 0}, {"-y"});
    stone.box({steleFace, 0.0f, -0.8f}, {steleFace + 0.7f, 0.55f, 0.8f}, {0, 0, 0}, {"-y"});
    MeshBuilder relief("relief");
    relief.grid(96, 96, [&](float s, float t) {
        // Plaque coordinates: x to the viewer's right (world -z, seen from the court), y up.
        float x = (0.5f - s) * 1.3f, y = (0.5f - t) * 1.3f;
        return glm::vec3(steleFace + lionRelief(x, y), 1.95f + y, x);
    });

    // Vases (lathe, metric UVs) and car-paint eggs and sphere: shared meshes placed by instances.
    std::vector<glm::vec2> vaseProfile;
    for (int i = 0; i <= 40; ++i) {
        float t = float(i) / 40.0f, y = 1.2f * t;
        float r = 0.13f + 0.22f * std::pow(std::max(0.0f, std::sin(kPi * std::min(t / 0.88f, 1.0f))), 1.3f) + 0.05f * std::max(0.0f, (t - 0.88f) / 0.12f);
        vaseProfile.push_back({r, y});
    }
    MeshBuilder vase("vase");
    vase.lathe({0, 0, 0}, vaseProfile, 48);
    std::vector<glm::vec2> eggProfile;
    for (int i = 0; i <= 48; ++i) {
        float theta = kPi * float(i) / 48.0f;
        eggProfile.push_back({0.36f * std::sin(theta) * (1.0f + 0.12f * std::cos(theta)), 0.55f * (1.0f - std::cos(theta))});
    }
    eggProfile.front().x = eggProfile.back().x = 0.0f;
    MeshBuilder egg("egg");
    egg.lathe({0, 0, 0}, eggProfile, 64);

    auto addMesh = [&](MeshData mesh) {
        scene.meshes.push_back(std::move(mesh));
        return uint32_t(scene.meshes.size() - 1);
    };
    const glm::mat4 identity(1.0f);
    scene.instances.push_back({addMesh(floor.finish()), FloorTiles, identity});
    scene.instances.push_back({addMesh(walls.finish()), Ashlar, identity});
    scene.instances.push_back({addMesh(stone.finish()), Stone, identity});
    scene.instances.push_back({addMesh(snow.finish()), Snow, identity});
    const uint32_t drapeMaterials[3] = {DrapeRed, DrapeBlue, DrapeGreen};
    for (int i = 0; i < 3; ++i) scene.instances.push_back({addMesh(drapes[i].finish()), drapeMaterials[i], identity});
    scene.instances.push_back({addMesh(relief.finish()), Bronze, identity});
    uint32_t vaseMesh = addMesh(vase.finish()), eggMesh = addMesh(egg.finish());
    for (int i = 0; i < 4; ++i)
        scene.instances.push_back({vaseMesh, i % 2 == 0 ? CarPaintRed : Terracotta,
                                   glm::translate(identity, glm::vec3(vaseSpots[i].x, 0.5f, vaseSpots[i].y))});
    scene.instances.push_back({eggMesh, CarPaintBlue, glm::translate(identity, glm::vec3(eggSpots[0].x, 1.0f, eggSpots[0].y))});
    scene.instances.push_back({eggMesh, CarPaintRed, glm::translate(identity, glm::vec3(eggSpots[1].x, 1.0f, eggSpots[1].y))});
    // The sphere as a lathe (u = local circumference, v = arc length) rather than makeUvSphere, whose u = r phi
    // stretches towards the poles.
    std::vector<glm::vec2> sphereProfile;
    for (int i = 0; i <= 48; ++i) {
        float theta = kPi * float(i) / 48.0f;
        sphereProfile.push_back({0.7f * std::sin(theta), -0.7f * std::cos(theta)});
    }
    sphereProfile.front().x = sphereProfile.back().x = 0.0f;
    MeshBuilder sphere("sphere");
    sphere.lathe({0, 0, 0}, sphereProfile, 96);
    uint32_t sphereMesh = addMesh(sphere.finish());
    scene.instances.push_back({sphereMesh, CarPaintBlue, glm::translate(identity, sphereCentre)});

    // Fallback camera and sun; content/atrium.json replaces them with the named walkthrough cameras and lights.
    Camera overview;
    overview.name = "overview";
    overview.position = {11.5f, 13.5f, 0.0f};   // above the east cornice, looking down the court
    overview.target = {-6.0f, 0.0f, 0.0f};
    overview.verticalFovDegrees = 62.0f;
    scene.cameras.push_back(overview);
    scene.lights.push_back({LightType::Directional, glm::normalize(glm::vec3(0.35f, 0.8f, 0.45f)), {1.0f, 0.95f, 0.86f}, 2.6f});
    return scene;
}

}  // namespace glimmer
