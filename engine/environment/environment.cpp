#include "environment/environment.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "core/clock.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "environment/cube_texels.h"
#include "environment/environment_cache.h"

namespace glimmer {

namespace {

constexpr int kBrdfLutSamples = 4096;    // per table entry and NDF (512 left 0.026 errors at n.v < 0.1)
constexpr int kLocalSize = 8;            // compute work-group edge (shaders/env/*.comp)

int levelCount(int size) {
    int levels = 1;
    while ((size >> levels) > 0) ++levels;
    return levels;
}

int groups(int size) { return (size + kLocalSize - 1) / kLocalSize; }

// Process-wide copy of the BRDF table: it depends on nothing but the BRDF, so later renderers (tests, batch
// renders in one process) upload it instead of recomputing it.
std::vector<float>& cachedBrdfLut() {
    static std::vector<float> table;
    return table;
}

gl::Texture createSourceCube() {
    GLuint cube = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &cube);
    glTextureStorage2D(cube, levelCount(Environment::kFaceSize), GL_RGBA32F, Environment::kFaceSize,
                       Environment::kFaceSize);
    glTextureParameteri(cube, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(cube, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(cube, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(cube, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(cube, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    return gl::Texture(cube);
}

gl::Texture createCubeArray(int levels, int faceSize, int cubes) {
    GLuint array = 0;
    glCreateTextures(GL_TEXTURE_CUBE_MAP_ARRAY, 1, &array);
    glTextureStorage3D(array, levels, GL_RGBA32F, faceSize, faceSize, 6 * cubes);
    glTextureParameteri(array, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(array, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(array, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(array, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return gl::Texture(array);
}

// Rung 0: the unfiltered map, one cube per NDF (the lookups index the layer by NDF).
gl::Texture createSpecularArray() { return createCubeArray(1, Environment::kFaceSize, 2); }

// Rungs 1 .. kRungs (Environment::kRungs).
gl::Texture createSpecularFineArray() {
    return createCubeArray(Environment::kFineLevels, Environment::kFaceSize / 2, 2 * Environment::kSublevels);
}

gl::Texture createBrdfLut() {
    gl::Texture lut = gl::createTexture2D(GL_RGBA32F, Environment::kBrdfLutSize, Environment::kBrdfLutSize, 1);
    glTextureParameteri(lut.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(lut.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return lut;
}

// The compute shaders that build the maps (their expanded sources are part of the cache key).
constexpr const char* kEnvironmentShaders[] = {"environment/equirect_to_cube.comp", "environment/procedural_sky.comp",
                                               "environment/prefilter.comp", "environment/radiance_centroid.comp", "environment/resample_cube.comp",
                                               "environment/brdf_lut.comp"};

void finishAndTime(double& slot, Stopwatch& clock) {
    glFinish();
    slot = clock.elapsedMs();
    clock.restart();
}

}  // namespace

EnvironmentSpec parseEnvironmentSpec(const std::string& text, const std::string& flag) {
    EnvironmentSpec spec;
    if (text.empty() || text == "procedural") return spec;
    if (text == "none") {
        spec.kind = EnvironmentSpec::Kind::None;
        return spec;
    }
    const std::string prefix = "constant:";
    if (text.rfind(prefix, 0) == 0) {
        spec.kind = EnvironmentSpec::Kind::Constant;
        std::vector<float> values;
        std::stringstream in(text.substr(prefix.size()));
        std::string item;
        while (std::getline(in, item, ',')) {
            size_t used = 0;
            float v = 0.0f;
            try {
                v = std::stof(item, &used);
            } catch (...) {
                used = 0;
            }
            if (used == 0 || used != item.size() || !std::isfinite(v) || v < 0.0f)
                throw UsageError(flag + ": " + text + ": expected constant:R,G,B with finite values >= 0");
            values.push_back(v);
        }
        if (values.size() == 1) spec.constant = glm::vec3(values[0]);
        else if (values.size() == 3) spec.constant = {values[0], values[1], values[2]};
        else throw UsageError(flag + ": " + text + ": expected constant:R,G,B or constant:V");
        return spec;
    }
    spec.kind = EnvironmentSpec::Kind::File;
    spec.path = text;
    return spec;
}

SunDescription sunFromScene(const Scene& scene) {
    SunDescription sun;
    for (const Light& light : scene.lights)
        if (light.type == LightType::Directional) {
            sun.analytic = true;
            sun.direction = glm::normalize(light.vector);
            sun.irradiance = light.color * light.intensity;
            return sun;
        }
    sun.direction = glm::normalize(sun.direction);
    return sun;
}

Environment::Environment(std::filesystem::path shaderRoot) : shaderRoot_(std::move(shaderRoot)) {
    uniforms_ = gl::createBuffer(sizeof(EnvironmentUniforms), nullptr);
}

static gl::Program computeProgram(const std::filesystem::path& root, const char* name, const char* file) {
    return gl::Program(root, {name, {{GL_COMPUTE_SHADER, file}}});
}

void Environment::update(const std::string& text, const SunDescription& sun, const std::string& flag, bool preview) {
    EnvironmentSpec spec = parseEnvironmentSpec(text, flag);
    std::ostringstream key;
    switch (spec.kind) {
        case EnvironmentSpec::Kind::None: key << "none"; break;
        case EnvironmentSpec::Kind::Constant:
            key << "constant " << spec.constant.x << ' ' << spec.constant.y << ' ' << spec.constant.z;
            break;
        case EnvironmentSpec::Kind::File: key << "file " << spec.path.string(); break;
        case EnvironmentSpec::Kind::Procedural:
            key << "procedural " << sun.analytic << ' ' << sun.direction.x << ' ' << sun.direction.y << ' '
                << sun.direction.z << ' ' << sun.irradiance.x << ' ' << sun.irradiance.y << ' ' << sun.irradiance.z;
            break;
    }
    if (key.str() == activeKey_) return;
    contentKey_.clear();
    prefilterJob_.reset();   // its source is about to go

    if (spec.kind == EnvironmentSpec::Kind::None) {
        sourceCube_.reset();
        specular_.reset();
        specularFine_.reset();
        enabled_ = false;
        refined_ = true;
        active_ = spec;
        activeKey_ = key.str();
        timings_ = {};
        return;
    }

    if (spec.kind == EnvironmentSpec::Kind::File) {
        // Fail early on a missing file. buildMaps decodes the image before it replaces any texture, so a bad file
        // leaves the previous environment in place.
        std::error_code ec;
        if (!std::filesystem::is_regular_file(spec.path, ec))
            throw Error(flag + ": " + spec.path.string() + ": file not found");
    }
    Stopwatch total;
    std::optional<EnvironmentCache> cache;
    const std::string parameters = cacheParameters(spec, sun);
    if (!parameters.empty()) {
        cache.emplace(cache::defaultCacheDir(), parameters);
        if (loadFromCache(*cache)) {
            timings_ = {};
            timings_.loadMs = timings_.totalMs = total.elapsedMs();
            timings_.cacheHit = true;
            active_ = spec;
            activeKey_ = key.str();
            contentKey_ = parameters;
            enabled_ = true;
            refined_ = true;
            log::info("environment ", text.empty() ? std::string("procedural") : text, ": read from the cache (",
                      cache->fileName(), ") in ", timings_.totalMs, " ms");
            return;
        }
    }
    if (!equirectProgram_) {
        equirectProgram_ = computeProgram(shaderRoot_, "env/equirect_to_cube", "environment/equirect_to_cube.comp");
        skyProgram_ = computeProgram(shaderRoot_, "env/procedural_sky", "environment/procedural_sky.comp");
        prefilter_ = std::make_unique<CubePrefilter>(shaderRoot_);
        lutProgram_ = computeProgram(shaderRoot_, "env/brdf_lut", "environment/brdf_lut.comp");
    }
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    double lutMs = 0.0;
    if (!brdfLut_) {
        Stopwatch clock;
        buildBrdfLut();
        lutMs = clock.elapsedMs();
    }
    try {
        buildMaps(spec, sun);
    } catch (const Error& e) {
        std::string message = e.what();   // one line: decoder messages may span several
        std::replace(message.begin(), message.end(), '\n', ' ');
        throw Error(flag + ": " + message);
    }
    timings_.brdfLutMs = lutMs;
    active_ = spec;
    activeKey_ = key.str();
    enabled_ = true;
    refined_ = false;
    refineCacheParameters_ = parameters;
    if (preview) {
        fillPreview();
        timings_.totalMs = total.elapsedMs();
        log::info("environment ", text.empty() ? std::string("procedural") : text, ": a preview in ",
                  timings_.totalMs, " ms (box-filtered mips for the specular rungs); the prefilter follows");
        return;
    }
    timings_.totalMs = total.elapsedMs();
    refine();
}

void Environment::refine() {
    while (!refineStep()) {}
}

bool Environment::refineStep() {
    if (refined_) return true;
    Stopwatch clock;
    if (!prefilterJob_) prefilterJob_ = prefilter_->begin(sourceCube_.id(), kFaceSize, prefilterLevels(), 0x3u);
    const bool done = prefilter_->step(*prefilterJob_);
    glFinish();
    timings_.prefilterMs += clock.elapsedMs();
    if (!done) return false;
    prefilterJob_.reset();
    clock.restart();
    if (!refineCacheParameters_.empty()) {
        EnvironmentCache cache(cache::defaultCacheDir(), refineCacheParameters_);
        timings_.cacheStored = cache.store({sourceCube_.id(), specular_.id(), specularFine_.id(), brdfLut_.id()}, sh_);
        timings_.cacheStoreMs = clock.elapsedMs();
    }
    timings_.totalMs += timings_.prefilterMs + timings_.cacheStoreMs;
    contentKey_ = refineCacheParameters_;
    refined_ = true;
    const std::string name = active_.kind == EnvironmentSpec::Kind::File ? active_.path.string() : "procedural";
    log::info("environment ", name, ": load ", timings_.loadMs, " ms, cubemap ", timings_.convertMs, " ms, mips ",
              timings_.mipsMs, " ms, prefilter ", timings_.prefilterMs, " ms, irradiance SH ",
              timings_.irradianceMs, " ms, BRDF table ", timings_.brdfLutMs, " ms, total ", timings_.totalMs, " ms");
    return true;
}

std::pair<int, int> Environment::refineProgress() const {
    if (refined_) return {1, 1};
    if (!prefilterJob_) return {0, 1};
    return {int(prefilterJob_->nextGroup), prefilterJob_->groupCount()};
}

void Environment::fillPreview() {
    // Each rung from the source's box-filtered mip whose texels are about as wide as the rung's lobe (2 alpha
    // radians; a mip k texel spans about (pi / 2) / (kFaceSize >> k)), resampled bilinearly into the rung's face
    // size: blurrier at the horizon and blockier than the quadrature, but a few milliseconds instead of seconds.
    GLuint view = 0;
    glGenTextures(1, &view);
    glTextureView(view, GL_TEXTURE_CUBE_MAP_ARRAY, sourceCube_.id(), GL_RGBA32F, 0, GLuint(levelCount(kFaceSize)), 0, 6);
    gl::Texture sourceArray(view);
    glTextureParameteri(view, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
    glTextureParameteri(view, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    const int coarsest = levelCount(kFaceSize) - 1;
    for (int rung = 1; rung <= kRungs; ++rung) {
        const float texelsPerLobe = 2.0f * rungAlpha(rung) * float(kFaceSize) / 1.5707964f;
        const int sourceMip = std::clamp(int(std::lround(std::log2(std::max(texelsPerLobe, 1.0f)))), 0, coarsest);
        const int mip = rungMip(rung);
        for (int ndf = 0; ndf < 2; ++ndf)
            prefilter_->resample(sourceArray.id(), 0, sourceMip, specularFine_.id(), mip, (kFaceSize / 2) >> mip,
                                 6 * rungCube(rung, ndf));
    }
    glFinish();
}

std::string Environment::cacheParameters(const EnvironmentSpec& spec, const SunDescription& sun) const {
    if (!EnvironmentCache::enabledByEnvironment()) return "";
    char text[512];
    std::string what;
    switch (spec.kind) {
        case EnvironmentSpec::Kind::File: {
            std::string hash = cache::fileContentHash(spec.path);
            if (hash.empty()) return "";
            what = "file " + hash;
            break;
        }
        case EnvironmentSpec::Kind::Constant:
            std::snprintf(text, sizeof text, "constant %.9g %.9g %.9g", spec.constant.x, spec.constant.y,
                          spec.constant.z);
            what = text;
            break;
        case EnvironmentSpec::Kind::Procedural:
            std::snprintf(text, sizeof text, "procedural analytic=%d direction=%.9g,%.9g,%.9g irradiance=%.9g,%.9g,%.9g",
                          int(sun.analytic), sun.direction.x, sun.direction.y, sun.direction.z, sun.irradiance.x,
                          sun.irradiance.y, sun.irradiance.z);
            what = text;
            break;
        case EnvironmentSpec::Kind::None: return "";
    }
    std::string shaders;
    for (const char* file : kEnvironmentShaders)
        shaders += gl::expandShaderSource(shaderRoot_, file, {file, {{GL_COMPUTE_SHADER, file}}}).text;
    std::snprintf(text, sizeof text,
                  " | face %d, rungs %d from alpha %g, %d a mip, prefilter quadrature refine %g roots mip %d, brdf "
                  "table %d x %d samples, irradiance face %d | shaders %s",
                  kFaceSize, kRungs, double(kRungAlphaMin), kSublevels, double(CubePrefilter::refine()),
                  CubePrefilter::rootMip(kFaceSize),
                  kBrdfLutSize, kBrdfLutSamples, kIrradianceFace,
                  cache::contentHash(shaders).c_str());
    return what + text;
}

bool Environment::loadFromCache(const EnvironmentCache& cache) {
    // Into new textures: a miss or a bad file leaves the current environment as it was.
    gl::Texture source = createSourceCube(), specular = createSpecularArray(), fine = createSpecularFineArray(),
                lut = createBrdfLut();
    std::array<glm::vec3, 9> sh{};
    if (!cache.load({source.id(), specular.id(), fine.id(), lut.id()}, sh)) return false;
    sourceCube_ = std::move(source);
    specular_ = std::move(specular);
    specularFine_ = std::move(fine);
    sh_ = sh;
    if (!brdfLut_) {
        brdfLut_ = std::move(lut);
        std::vector<float>& cached = cachedBrdfLut();
        if (cached.empty()) {
            cached.resize(size_t(kBrdfLutSize) * kBrdfLutSize * 4);
            glGetTextureImage(brdfLut_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(cached.size() * sizeof(float)),
                              cached.data());
        }
    }
    return true;
}

void Environment::buildBrdfLut() {
    brdfLut_ = createBrdfLut();
    std::vector<float>& cached = cachedBrdfLut();
    if (!cached.empty()) {
        glTextureSubImage2D(brdfLut_.id(), 0, 0, 0, kBrdfLutSize, kBrdfLutSize, GL_RGBA, GL_FLOAT, cached.data());
        return;
    }
    lutProgram_.use();
    glUniform1i(0, kBrdfLutSize);
    glUniform1i(1, kBrdfLutSamples);
    glBindImageTexture(IMAGE_ENV_OUTPUT, brdfLut_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(groups(kBrdfLutSize), groups(kBrdfLutSize), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    cached.resize(size_t(kBrdfLutSize) * kBrdfLutSize * 4);
    glGetTextureImage(brdfLut_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(cached.size() * sizeof(float)), cached.data());
}

void Environment::fillProceduralSky(const SunDescription& sun, bool drawSun) {
    skyProgram_.use();
    glUniform1i(0, kFaceSize);
    glUniform3fv(1, 1, glm::value_ptr(sun.direction));
    glUniform3fv(2, 1, glm::value_ptr(sun.irradiance));
    glUniform1i(3, drawSun ? 1 : 0);
    glBindImageTexture(IMAGE_ENV_OUTPUT, sourceCube_.id(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute(groups(kFaceSize), groups(kFaceSize), 6);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
}

void Environment::buildMaps(const EnvironmentSpec& spec, const SunDescription& sun) {
    timings_ = {};
    Stopwatch clock;
    gl::Texture equirect;
    if (spec.kind == EnvironmentSpec::Kind::File) {
        ImageF image = readImage(spec.path, ImageUse::Environment);
        if (image.width < 2 || image.height < 2 || image.channels < 1)
            throw Error(spec.path.string() + ": not an environment image (" + std::to_string(image.width) + "x" +
                        std::to_string(image.height) + ", " + std::to_string(image.channels) + " channels)");
        // RGBA with non-finite or negative values zeroed: NaN/Inf must not reach the framebuffer.
        std::vector<float> rgba(size_t(image.width) * image.height * 4, 1.0f);
        size_t bad = 0;
        for (size_t p = 0; p < size_t(image.width) * image.height; ++p)
            for (int c = 0; c < 3; ++c) {
                // Grey (or grey + alpha) images give the same value to R, G and B.
                float v = image.pixels[p * image.channels + (image.channels >= 3 ? c : 0)];
                if (!std::isfinite(v) || v < 0.0f) { v = 0.0f; ++bad; }
                rgba[p * 4 + c] = v;
            }
        if (bad) log::warn(spec.path.string(), ": ", bad, " negative or non-finite values set to 0");
        GLint maxSize = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
        if (image.width > maxSize || image.height > maxSize)
            throw Error(spec.path.string() + ": " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                        " exceeds the GL texture size limit " + std::to_string(maxSize));
        equirect = gl::createTexture2D(GL_RGBA32F, image.width, image.height, 1);
        glTextureSubImage2D(equirect.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rgba.data());
        glTextureParameteri(equirect.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(equirect.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(equirect.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
        finishAndTime(timings_.loadMs, clock);
    }

    sourceCube_ = createSourceCube();
    GLuint cube = sourceCube_.id();

    switch (spec.kind) {
        case EnvironmentSpec::Kind::File:
            equirectProgram_.use();
            glUniform1i(0, kFaceSize);
            glBindTextureUnit(UNIT_ENV_INPUT, equirect.id());
            glBindImageTexture(IMAGE_ENV_OUTPUT, cube, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
            glDispatchCompute(groups(kFaceSize), groups(kFaceSize), 6);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
            break;
        case EnvironmentSpec::Kind::Constant: {
            glm::vec4 value(spec.constant, 1.0f);
            glClearTexImage(cube, 0, GL_RGBA, GL_FLOAT, glm::value_ptr(value));
            break;
        }
        default: fillProceduralSky(sun, true); break;
    }

    specular_ = createSpecularArray();
    specularFine_ = createSpecularFineArray();
    GLuint array = specular_.id();
    // Level 0 of both NDF layers is the unfiltered source: the background and mirror reflections.
    for (int layer = 0; layer < 2; ++layer)
        glCopyImageSubData(cube, GL_TEXTURE_CUBE_MAP, 0, 0, 0, 0, array, GL_TEXTURE_CUBE_MAP_ARRAY, 0, 0, 0, 6 * layer,
                           kFaceSize, kFaceSize, 6);
    // An analytic directional light already carries the sun: light with the sky alone (see SunDescription).
    if (spec.kind == EnvironmentSpec::Kind::Procedural && sun.analytic) fillProceduralSky(sun, false);
    finishAndTime(timings_.convertMs, clock);

    glGenerateTextureMipmap(cube);
    finishAndTime(timings_.mipsMs, clock);
    projectIrradiance();
    timings_.irradianceMs = clock.elapsedMs();
}

namespace {
// Faces over 32 are filtered at the smallest power of two >= 1.6 / alpha (rungs 1 and 2 at 64, the rest at 32 or
// 16) and upsampled bilinearly; not below 32 under alpha 0.5, where smaller faces misplace small lamps, nor below 16
// above it, where they bend the rough lobes' horizon kink (the errors measured: docs/measurements.md).
int computedFaceSize(float alpha, int size) {
    int least = alpha < 0.5f ? 32 : 16;
    if (size <= least) return size;
    int computed = least;
    while (computed < size && float(computed) * alpha < 1.6f) computed *= 2;
    return computed;
}
}  // namespace

std::vector<CubePrefilter::Level> Environment::prefilterLevels() const {
    std::vector<CubePrefilter::Level> levels;
    for (int rung = 1; rung <= kRungs; ++rung) {
        CubePrefilter::Level level;
        level.alpha = rungAlpha(rung);
        level.target = specularFine_.id();
        level.mip = rungMip(rung);
        level.size = (kFaceSize / 2) >> level.mip;
        for (int ndf = 0; ndf < 2; ++ndf) level.layerFace[ndf] = 6 * rungCube(rung, ndf);
        level.computedSize = computedFaceSize(level.alpha, level.size);
        levels.push_back(level);
    }
    return levels;
}

void Environment::projectIrradiance() {
    // Project a small source mip on the 9 real SH basis functions (texel solid angles exact), then convolve with
    // the clamped cosine (Ramamoorthi & Hanrahan 2001, Eq. 8: A0 = pi, A1 = 2 pi / 3, A2 = pi / 4) and divide
    // by pi, so the shader's sum is the radiance a white Lambertian surface reflects.
    int level = 0;
    while ((kFaceSize >> level) > kIrradianceFace) ++level;
    envref::CubeImage image;
    image.size = kFaceSize >> level;
    image.rgba.resize(size_t(6) * image.size * image.size * 4);
    glGetTextureImage(sourceCube_.id(), level, GL_RGBA, GL_FLOAT, GLsizei(image.rgba.size() * sizeof(float)),
                      image.rgba.data());
    std::array<glm::dvec3, 9> sum{};
    for (int face = 0; face < 6; ++face)
        for (int y = 0; y < image.size; ++y)
            for (int x = 0; x < image.size; ++x) {
                glm::dvec3 d(envref::cubeTexelDirection(face, x, y, image.size));
                double solidAngle = envref::cubeTexelSolidAngle(x, y, image.size);
                glm::dvec3 radiance = glm::dvec3(image.texel(face, x, y)) * solidAngle;
                const double basis[9] = {0.282095, 0.488603 * d.y, 0.488603 * d.z, 0.488603 * d.x,
                                         1.092548 * d.x * d.y, 1.092548 * d.y * d.z,
                                         0.315392 * (3.0 * d.z * d.z - 1.0), 1.092548 * d.x * d.z,
                                         0.546274 * (d.x * d.x - d.y * d.y)};
                for (int i = 0; i < 9; ++i) sum[i] += radiance * basis[i];
            }
    const double band[9] = {1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25};  // A_l / pi
    for (int i = 0; i < 9; ++i) sh_[i] = glm::vec3(sum[i] * band[i]);
}

void Environment::bind(float intensity, float rotationDegrees) {
    EnvironmentUniforms u{};
    for (int i = 0; i < 9; ++i) u.sh[i] = glm::vec4(sh_[i], 0.0f);
    float radians = glm::radians(active_.kind == EnvironmentSpec::Kind::Procedural ? 0.0f : rotationDegrees);
    u.params = {intensity, enabled_ ? 1.0f : 0.0f, float(kRungs - 1), kRungAlphaMin};
    u.rotation = {std::cos(radians), std::sin(radians), 0.0f, 0.0f};
    glNamedBufferSubData(uniforms_.id(), 0, sizeof(u), &u);
    glBindBufferBase(GL_UNIFORM_BUFFER, kEnvironmentBinding, uniforms_.id());
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glBindTextureUnit(kEnvironmentSpecularUnit, enabled_ ? specular_.id() : 0);
    glBindTextureUnit(kEnvironmentSpecularFineUnit, enabled_ ? specularFine_.id() : 0);
    glBindTextureUnit(kEnvironmentBrdfLutUnit, enabled_ ? brdfLut_.id() : 0);
    glBindTextureUnit(kEnvironmentSourceUnit, enabled_ ? sourceCube_.id() : 0);
}

nlohmann::json Environment::stats() const {
    const char* kinds[] = {"procedural", "none", "constant", "file"};
    nlohmann::json j = {{"kind", kinds[int(active_.kind)]}, {"enabled", enabled_}, {"refined", refined_}};
    if (active_.kind == EnvironmentSpec::Kind::File) j["path"] = active_.path.string();
    if (enabled_) {
        j["face_size"] = kFaceSize;
        j["prefilter_rungs"] = kRungs;
        j["prefilter_rung_alpha_min"] = kRungAlphaMin;
        j["prefilter_refine"] = CubePrefilter::refine();
        j["brdf_lut_size"] = kBrdfLutSize;
        j["precompute_ms"] = {{"load", timings_.loadMs},           {"cubemap", timings_.convertMs},
                              {"mips", timings_.mipsMs},           {"prefilter", timings_.prefilterMs},
                              {"irradiance_sh", timings_.irradianceMs}, {"brdf_lut", timings_.brdfLutMs},
                              {"total", timings_.totalMs}};
        j["cache"] = {{"enabled", EnvironmentCache::enabledByEnvironment()},
                      {"hit", timings_.cacheHit},
                      {"stored", timings_.cacheStored},
                      {"store_ms", timings_.cacheStoreMs}};
    }
    return j;
}

}  // namespace glimmer
