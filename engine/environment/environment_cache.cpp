#include "environment/environment_cache.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace glimmer {

namespace {

constexpr uint32_t kLayoutVersion = 1;   // bump when the payload layout below changes
constexpr size_t kShFloats = 9 * 3;

struct LevelShape {
    int width, height, depth;  // depth: cube faces (x layers) or 1
};

std::vector<LevelShape> levelShapes(GLuint texture) {
    GLint target = 0, levels = 0;
    glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
    glGetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
    std::vector<LevelShape> shapes;
    for (int level = 0; level < levels; ++level) {
        LevelShape s{};
        glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_WIDTH, &s.width);
        glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_HEIGHT, &s.height);
        glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_DEPTH, &s.depth);
        if (target == GL_TEXTURE_CUBE_MAP) s.depth = 6;
        shapes.push_back(s);
    }
    return shapes;
}

size_t levelBytes(const LevelShape& s) { return size_t(s.width) * s.height * s.depth * 4 * sizeof(float); }

size_t payloadBytes(const std::vector<GLuint>& textures) {
    size_t bytes = kShFloats * sizeof(float);
    for (GLuint t : textures) bytes += textureLevelBytes(t);
    return bytes;
}

bool finiteAndNonNegative(std::string_view payload) {
    const size_t n = payload.size() / sizeof(float);
    for (size_t i = 0; i < n; ++i) {
        float v;
        std::memcpy(&v, payload.data() + i * sizeof(float), sizeof v);
        if (!std::isfinite(v)) return false;
    }
    // SH coefficients are signed; every texel value is a radiance (or an alpha of 1) and must be >= 0.
    for (size_t i = 0; i + kShFloats < n; ++i) {
        float v;
        std::memcpy(&v, payload.data() + i * sizeof(float), sizeof v);
        if (v < 0.0f) return false;
    }
    return true;
}

}  // namespace

size_t textureLevelBytes(GLuint texture) {
    size_t bytes = 0;
    for (const LevelShape& s : levelShapes(texture)) bytes += levelBytes(s);
    return bytes;
}

bool EnvironmentCache::enabledByEnvironment() {
    const char* v = std::getenv("GLIMMER_ENV_CACHE");
    return !(v && std::string(v) == "0");
}

EnvironmentCache::EnvironmentCache(std::filesystem::path dir, std::string parameters)
    : dir_(std::move(dir)), key_{"environment", kLayoutVersion, std::move(parameters)} {
    fileName_ = "environment_" + cache::contentHash(key_.parameters) + ".bin";
}

bool EnvironmentCache::load(const std::vector<GLuint>& textures, std::array<glm::vec3, 9>& sh) const {
    std::optional<std::string> payload = dir_.load(fileName_, key_, payloadBytes(textures), finiteAndNonNegative);
    if (!payload) return false;
    size_t offset = 0;
    for (GLuint t : textures) {
        std::vector<LevelShape> shapes = levelShapes(t);
        GLint target = 0;
        glGetTextureParameteriv(t, GL_TEXTURE_TARGET, &target);
        const bool cube = target == GL_TEXTURE_CUBE_MAP || target == GL_TEXTURE_CUBE_MAP_ARRAY;
        for (size_t level = 0; level < shapes.size(); ++level) {
            const LevelShape& s = shapes[level];
            if (s.depth == 1 && !cube)
                glTextureSubImage2D(t, GLint(level), 0, 0, s.width, s.height, GL_RGBA, GL_FLOAT, payload->data() + offset);
            else   // cube maps and cube map arrays take their faces as layers (GL 4.5 DSA)
                glTextureSubImage3D(t, GLint(level), 0, 0, 0, s.width, s.height, s.depth, GL_RGBA, GL_FLOAT,
                                    payload->data() + offset);
            offset += levelBytes(s);
        }
    }
    // Little-endian host assumed throughout the cache (the checksummed header was written by this machine type).
    std::memcpy(sh.data(), payload->data() + offset, kShFloats * sizeof(float));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    return true;
}

bool EnvironmentCache::store(const std::vector<GLuint>& textures, const std::array<glm::vec3, 9>& sh) const {
    std::string payload;
    payload.reserve(payloadBytes(textures));
    for (GLuint t : textures) {
        std::vector<LevelShape> shapes = levelShapes(t);
        for (size_t level = 0; level < shapes.size(); ++level) {
            size_t bytes = levelBytes(shapes[level]);
            size_t at = payload.size();
            payload.resize(at + bytes);
            glGetTextureImage(t, GLint(level), GL_RGBA, GL_FLOAT, GLsizei(bytes), payload.data() + at);
        }
    }
    payload.append(reinterpret_cast<const char*>(sh.data()), kShFloats * sizeof(float));
    if (!finiteAndNonNegative(payload)) return false;   // never cache what a later load would reject
    bool stored = dir_.store(fileName_, key_, payload);
    if (stored) pruneOldFiles();
    return stored;
}

void EnvironmentCache::pruneOldFiles() const {
    dir_.pruneLeastRecentlyUsed("environment_", ".bin", cache::keptFilesPerKind(size_t(kMaxFiles)));
}

}  // namespace glimmer
