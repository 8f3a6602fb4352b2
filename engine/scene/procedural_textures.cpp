#include "scene/procedural_textures.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

namespace glimmer {
namespace {

uint32_t hash2(int x, int y, uint32_t seed) {
    uint32_t h = uint32_t(x) * 0x8da6b343u ^ uint32_t(y) * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return h;
}

float random01(int x, int y, uint32_t seed) { return float(hash2(x, y, seed) & 0xffffffu) / float(0xffffff); }

// Periodic value noise: the lattice wraps every `period` cells, so the texture tiles.
float valueNoise(float x, float y, int period, uint32_t seed) {
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    float fx = x - float(x0), fy = y - float(y0);
    auto wrap = [period](int v) { return ((v % period) + period) % period; };
    auto at = [&](int i, int j) { return random01(wrap(i), wrap(j), seed); };
    float sx = fx * fx * (3.0f - 2.0f * fx), sy = fy * fy * (3.0f - 2.0f * fy);
    float a = glm::mix(at(x0, y0), at(x0 + 1, y0), sx), b = glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), sx);
    return glm::mix(a, b, sy);
}

// Fractal noise in [0,1] over texture coordinates s, t in [0,1), periodic; `cells` lattice cells at the base octave.
float fractalNoise(float s, float t, int cells, int octaves, uint32_t seed) {
    float sum = 0.0f, weight = 0.5f, total = 0.0f;
    for (int o = 0; o < octaves; ++o) {
        int period = cells << o;
        sum += weight * valueNoise(s * period, t * period, period, seed + uint32_t(o) * 101u);
        total += weight;
        weight *= 0.5f;
    }
    return sum / total;
}

uint8_t toSrgb8(float linear) {
    linear = std::clamp(linear, 0.0f, 1.0f);
    float s = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(s * 255.0f));
}

// Fills an sRGB texture from a function of (x, y) in metres over one period.
TextureData fill(const char* name, int size, float period, const std::function<glm::vec3(float, float, float, float)>& colour) {
    TextureData t;
    t.name = name;
    t.width = t.height = size;
    t.srgb = true;
    t.rgba.resize(size_t(size) * size * 4);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            float s = (x + 0.5f) / size, u = (y + 0.5f) / size;
            glm::vec3 c = colour(s * period, u * period, s, u);
            uint8_t* p = &t.rgba[(size_t(y) * size + x) * 4];
            p[0] = toSrgb8(c.x);
            p[1] = toSrgb8(c.y);
            p[2] = toSrgb8(c.z);
            p[3] = 255;
        }
    return t;
}

// Distance-based joint mask: 1 inside a block, 0 in the joint, with a soft edge `soft` metres wide.
float jointMask(float distanceToEdge, float halfJoint, float soft) {
    return std::clamp((distanceToEdge - halfJoint) / soft, 0.0f, 1.0f);
}

}  // namespace

TextureData makeAshlarTexture(int size, float period) {
    const float courseHeight = 0.5f, blockLength = 1.0f;
    const int courses = int(std::lround(period / courseHeight));
    return fill("ashlar", size, period, [=](float x, float y, float s, float t) {
        int course = int(std::floor(y / courseHeight));
        float shift = (course % 2) * 0.5f * blockLength;
        float bx = x + shift;
        int block = int(std::floor(bx / blockLength));
        float fx = bx - block * blockLength, fy = y - course * courseHeight;
        float edge = std::min(std::min(fx, blockLength - fx), std::min(fy, courseHeight - fy));
        float mask = jointMask(edge, 0.008f, 0.006f);
        int wrappedBlock = ((block % int(period / blockLength)) + int(period / blockLength)) % int(period / blockLength);
        float tint = random01(wrappedBlock, course % courses, 7u);
        float grain = fractalNoise(s, t, 16, 4, 11u);
        glm::vec3 stone = glm::mix(glm::vec3(0.40f, 0.30f, 0.19f), glm::vec3(0.52f, 0.41f, 0.27f), tint);
        stone *= 0.8f + 0.4f * grain;
        glm::vec3 mortar(0.30f, 0.28f, 0.25f);
        return glm::mix(mortar, stone, mask);
    });
}

TextureData makeStoneTexture(int size, float period) {
    return fill("stone", size, period, [](float, float, float s, float t) {
        float broad = fractalNoise(s, t, 4, 3, 21u), fine = fractalNoise(s, t, 32, 3, 23u);
        glm::vec3 base = glm::mix(glm::vec3(0.36f, 0.30f, 0.22f), glm::vec3(0.50f, 0.43f, 0.32f), broad);
        return base * (0.85f + 0.3f * fine);
    });
}

TextureData makeFloorTileTexture(int size, float period, float tile) {
    const int tilesPerPeriod = std::max(1, int(std::lround(period / tile)));
    return fill("floor_tiles", size, period, [=](float x, float y, float s, float t) {
        int i = int(std::floor(x / tile)), j = int(std::floor(y / tile));
        float fx = x - i * tile, fy = y - j * tile;
        float edge = std::min(std::min(fx, tile - fx), std::min(fy, tile - fy));
        float mask = jointMask(edge, 0.004f, 0.004f);
        bool dark = ((i + j) % 2) != 0;
        // Marble: veins from a sine warped by noise, per-tile offset so neighbours differ.
        float offset = random01(i % tilesPerPeriod, j % tilesPerPeriod, 31u) * 6.28f;
        float warp = fractalNoise(s, t, 8, 4, dark ? 41u : 43u);
        float vein = 0.5f + 0.5f * std::sin((x + y) * 9.0f + warp * 9.0f + offset);
        vein = std::pow(vein, 8.0f);
        glm::vec3 marble = dark ? glm::vec3(0.23f, 0.13f, 0.09f) : glm::vec3(0.70f, 0.66f, 0.58f);
        glm::vec3 veinColour = dark ? glm::vec3(0.45f, 0.35f, 0.28f) : glm::vec3(0.45f, 0.42f, 0.38f);
        glm::vec3 c = glm::mix(marble, veinColour, 0.6f * vein) * (0.92f + 0.16f * warp);
        return glm::mix(glm::vec3(0.18f, 0.17f, 0.16f), c, mask);
    });
}

}  // namespace glimmer
