#include "reference/discrete_facets/reference_render.h"

#include <glad/gl.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>

#include "common/bindings.glsl"
#include "core/error.h"
#include "core/log.h"
#include "gl/handles.h"
#include "gl/pipeline_state.h"
#include "gl/program.h"
#include "glints/methods.h"
#include "reference/discrete_facets/environment_glints.h"
#include "render/aov.h"

namespace glimmer::facets {

namespace {

// What the CPU computed for the frame the `reference` method renders next: per pixel, one RGBA32F layer per light
// (rgb D_est, a 1 where evaluated), then optionally a layer of environment glints (rgb radiance to add). Shared
// between renderReference(), the method's GPU resources and its pass.
struct ReferenceFrameData {
    std::mutex mutex;
    int width = 0, height = 0, layers = 0;
    int environmentLayer = -1;   // >= 0: the layer the environment pass adds
    std::vector<float> rgba;     // layer-major, rows bottom-up
    uint64_t version = 0;
    GLuint texture = 0;          // the texture the resources last uploaded (owned by them)
};

ReferenceFrameData& frameData() {
    static ReferenceFrameData data;
    return data;
}

class ReferenceResources : public GlintMethodResources {
public:
    void bind() override {
        ReferenceFrameData& data = frameData();
        std::lock_guard<std::mutex> lock(data.mutex);
        if (data.version != uploaded_ || !texture_) {
            uploaded_ = data.version;
            GLuint id = 0;
            glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &id);
            texture_ = gl::Texture(id);
            const int w = std::max(data.width, 1), h = std::max(data.height, 1), layers = std::max(data.layers, 1);
            glTextureStorage3D(id, 1, GL_RGBA32F, w, h, layers);
            glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            if (!data.rgba.empty() && data.rgba.size() == size_t(w) * h * layers * 4)
                glTextureSubImage3D(id, 0, 0, 0, 0, w, h, layers, GL_RGBA, GL_FLOAT, data.rgba.data());
            else {
                const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
                glClearTexImage(id, 0, GL_RGBA, GL_FLOAT, zero);
            }
        }
        data.texture = texture_.id();
        glBindTextureUnit(UNIT_METHOD_FIRST, texture_.id());
    }
    ~ReferenceResources() override {
        ReferenceFrameData& data = frameData();
        std::lock_guard<std::mutex> lock(data.mutex);
        if (data.texture == texture_.id()) data.texture = 0;
    }

private:
    gl::Texture texture_;
    uint64_t uploaded_ = ~uint64_t(0);
};

// Adds the environment layer to the HDR radiance (frame.blendWeight: a running mean in accumulating IBL modes).
class EnvironmentGlintPass : public MethodPass {
public:
    explicit EnvironmentGlintPass(const std::filesystem::path& root)
        : program_(root, {"reference_environment",
                          {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                           {GL_FRAGMENT_SHADER, "glints/reference/reference_environment.frag"}}}) {}
    const char* name() const override { return "reference_environment_glints"; }
    std::vector<gl::Program*> programs() override { return {&program_}; }
    bool runs(const MethodPassFrame& frame) const override {
        ReferenceFrameData& data = frameData();
        std::lock_guard<std::mutex> lock(data.mutex);
        return frame.debugView == 0 && data.environmentLayer >= 0 && data.texture != 0;
    }
    void execute(const MethodPassFrame& frame) override {
        ReferenceFrameData& data = frameData();
        int layer;
        {
            std::lock_guard<std::mutex> lock(data.mutex);
            layer = data.environmentLayer;
            glBindTextureUnit(0, data.texture);
        }
        program_.use();
        glProgramUniform1i(program_.id(), 0, layer);
        glBindVertexArray(frame.emptyVao);
        gl::PipelineState state = gl::fullscreenState(frame.hdrFramebuffer, frame.width, frame.height);
        state.blend = {true, -1, GL_CONSTANT_ALPHA, GL_ONE, GL_ZERO, GL_ONE, {0.0f, 0.0f, 0.0f, frame.blendWeight}};
        state.apply();
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

private:
    gl::Program program_;
};

GlintMethod referenceMethod() {
    GlintMethod method{kReferenceMethodId,
                       "Exact discrete-facet reference (every facet of a fixed realization counted, CPU)",
                       "GLINT_METHOD_REFERENCE", "glints/reference/reference.glsl",
                       "the glint material's definition (README); Jakob et al. 2014, discrete stochastic microfacets",
                       {{"lobe", 0.0f, 0.0f, 1.0f,
                         "a facet's reflection lobe: the cone of half-angle gamma, or a Gaussian of the same solid angle",
                         {"cone", "gaussian"}},
                        {"footprint", 0.0f, 0.0f, 1.0f,
                         "pixel filter over the UV footprint: the parallelogram (box) or a Gaussian of its second moments",
                         {"box", "gaussian"}},
                        {"seed", 0.0f, 0.0f, 1e6f, "realization (material i uses seed x 2^20 + i)", {}, true},
                        {"threads", 0.0f, 0.0f, 256.0f, "CPU threads (0 = every hardware thread)", {}, true},
                        {"env_facet_samples", 4.0f, 1.0f, 64.0f,
                         "environment: half vectors per facet inside its lobe (stratified Monte Carlo over the map)", {},
                         true},
                        {"env_samples", 64.0f, 1.0f, 4096.0f,
                         "environment: samples of the smooth lobe subtracted (the IBL mode already shades it)", {}, true},
                        {"light_extent", 1.0f, 0.0f, 2.0f,
                         "lights of a size: integrate each facet's lobe over the light for area lights and point "
                         "lights of a radius (area), also over the sun's disk (all), or count the facets at every "
                         "light's centre direction (centre)",
                         {"centre", "area", "all"}},
                        {"light_facet_samples", 16.0f, 1.0f, 256.0f,
                         "extent: half vectors per facet lobe tested against the light (stratified)", {}, true},
                        {"light_samples", 1024.0f, 16.0f, 65536.0f,
                         "extent: directions over the light for the smooth expectation (stratified)", {}, true}}};
    method.createResources = [] { return std::make_unique<ReferenceResources>(); };
    method.createPasses = [](const std::filesystem::path& root) {
        MethodPassList passes;
        passes.push_back(std::make_unique<EnvironmentGlintPass>(root));
        return passes;
    };
    return method;
}

std::vector<float> renderAov(OffscreenSession& session, RenderRequest request, const char* aov) {
    request.settings.debugView = findAov(aov).viewId;
    return session.render(request).hdr;
}

}  // namespace

void registerReferenceMethod() {
    static std::once_flag once;
    std::call_once(once, [] { registerGlintMethod(referenceMethod()); });
}

ReferenceOptions referenceOptions(const RenderSettings& settings) {
    const GlintMethod& method = findGlintMethod(kReferenceMethodId);
    const ParamValues& values = settings.methodValues(kReferenceMethodId);
    auto value = [&](const char* name) {
        for (const ParamSpec& spec : method.params)
            if (spec.name == name) return paramOr(values, spec);
        return 0.0f;
    };
    ReferenceOptions options;
    options.lobe = value("lobe") > 0.5f ? Lobe::Gaussian : Lobe::Cone;
    options.filter = value("footprint") > 0.5f ? FootprintFilter::Gaussian : FootprintFilter::Box;
    options.seed = uint64_t(value("seed"));
    options.threads = int(value("threads"));
    options.lightExtent = int(std::lround(value("light_extent")));
    options.extended.facetSamples = int(value("light_facet_samples"));
    options.extended.lightSamples = int(value("light_samples"));
    return options;
}

SurfaceImage captureSurface(OffscreenSession& session, const RenderRequest& request) {
    RenderRequest r = request;
    r.settings.method = "smooth";
    r.frames = 1;
    r.spp = 1;
    const std::vector<float> normal = renderAov(session, r, "normal"), tangent = renderAov(session, r, "tangent"),
                             uv = renderAov(session, r, "uv"), duvdx = renderAov(session, r, "duvdx"),
                             duvdy = renderAov(session, r, "duvdy"), depth = renderAov(session, r, "depth"),
                             material = renderAov(session, r, "material"), albedo = renderAov(session, r, "albedo"),
                             ao = renderAov(session, r, "ao");
    const Camera& camera = request.cameraOverride ? *request.cameraOverride : session.scene().camera(request.camera);
    SurfaceImage surface;
    surface.width = request.width;
    surface.height = request.height;
    surface.cameraPosition = glm::dvec3(camera.position);
    surface.pixels.resize(size_t(surface.width) * size_t(surface.height));
    for (int y = 0; y < surface.height; ++y)
        for (int x = 0; x < surface.width; ++x) {
            const size_t i = size_t(y) * size_t(surface.width) + size_t(x), c = 4 * i;
            SurfacePixel& p = surface.pixels[i];
            const double distance = depth[c];
            p.covered = distance > 0.0 && std::isfinite(distance);
            if (!p.covered) continue;
            Ray ray = cameraRay(camera, surface.width, surface.height, double(x) + 0.5, double(y) + 0.5);
            p.position = ray.origin + distance * ray.direction;
            p.normal = {normal[c], normal[c + 1], normal[c + 2]};
            p.tangent = {tangent[c], tangent[c + 1], tangent[c + 2]};
            p.bitangentSign = tangent[c + 3] < 0.0f ? -1.0 : 1.0;
            p.footprint.uv = {uv[c], uv[c + 1]};
            p.footprint.duvdx = {duvdx[c], duvdx[c + 1]};
            p.footprint.duvdy = {duvdy[c], duvdy[c + 1]};
            p.material = int(std::lround(material[c + 2]));
            p.metallic = material[c + 1];
            p.baseColor = {albedo[c], albedo[c + 1], albedo[c + 2]};
            p.occlusion = ao[c];
        }
    return surface;
}

RenderResult renderReference(OffscreenSession& session, const RenderRequest& request) {
    // The facets are counted for the unjittered pixel footprint (the AOVs' frame 0): TAA may accumulate frames as
    // long as the lighting pass shades glints at that footprint too (taa.stable_glints, the default); SSAA
    // renders other pixels.
    const int aa = int(request.settings.value(param::aa));
    if (aa == 2 || (aa == 1 && request.settings.value(param::taa_stable_glints) < 0.5f))
        throw UsageError("--method reference: needs aa=off, or aa=taa with taa.stable_glints=1 (it counts the facets "
                         "of each pixel's unjittered footprint)");
    if (request.renderScale != 1.0f)
        throw UsageError("--method reference: needs --render-scale 1 (the facets are counted per render pixel)");
    registerReferenceMethod();
    const ReferenceOptions options = referenceOptions(request.settings);
    SurfaceImage surface = captureSurface(session, request);
    const Scene& scene = session.scene();
    // In the lighting pass's order (gpuLightOrder): the shader reads layer k for its light k.
    std::vector<Light> lights;
    for (size_t i : gpuLightOrder(scene.lights)) lights.push_back(scene.lights[i]);
    ReferenceImage image = evaluateLights(surface, scene.materials, lights, options);
    log::info("reference: ", image.width, "x", image.height, ", ", image.lights, " light(s), ", image.threads,
              " thread(s): ", image.seconds, " s, ", image.facetsTested, " facets tested");
    // The environment (final image only): the facets' reflection of the map the renderer uses.
    std::vector<glm::vec3> environment;
    double environmentSeconds = 0.0;
    session.context().makeCurrent();
    const Environment& env = session.renderer().environment();
    if (request.settings.debugView == 0 && env.enabled()) {
        envref::CubeImage cube;
        cube.size = Environment::kFaceSize;
        cube.rgba.resize(size_t(6) * cube.size * cube.size * 4);
        glGetTextureImage(env.sourceCube(), 0, GL_RGBA, GL_FLOAT, GLsizei(cube.rgba.size() * sizeof(float)), cube.rgba.data());
        const bool procedural = env.stats().value("kind", std::string()) == "procedural";
        EnvironmentMap map(std::move(cube), request.settings.value(param::env_intensity),
                           procedural ? 0.0 : request.settings.value(param::env_rotation));
        const ParamValues& values = request.settings.methodValues(kReferenceMethodId);
        EnvironmentOptions environmentOptions;
        for (const ParamSpec& spec : findGlintMethod(kReferenceMethodId).params) {
            if (spec.name == "env_facet_samples") environmentOptions.facetSamples = int(paramOr(values, spec));
            if (spec.name == "env_samples") environmentOptions.smoothSamples = int(paramOr(values, spec));
        }
        environment = environmentGlints(surface, scene.materials, map, options, environmentOptions, &environmentSeconds);
        log::info("reference: environment glints ", environmentSeconds, " s");
    }
    {
        ReferenceFrameData& data = frameData();
        std::lock_guard<std::mutex> lock(data.mutex);
        data.width = image.width;
        data.height = image.height;
        data.layers = std::max(image.lights + (environment.empty() ? 0 : 1), 1);
        data.environmentLayer = environment.empty() ? -1 : image.lights;
        data.rgba.assign(size_t(data.width) * data.height * data.layers * 4, 0.0f);
        const size_t pixels = size_t(data.width) * data.height;
        for (int k = 0; k < image.lights; ++k)
            for (size_t p = 0; p < pixels; ++p) {
                float* out = &data.rgba[(size_t(k) * pixels + p) * 4];
                const glm::vec3 d = image.d[p * size_t(image.lights) + size_t(k)];
                out[0] = d.x;
                out[1] = d.y;
                out[2] = d.z;
                out[3] = image.glinty[p] ? 1.0f : 0.0f;
            }
        if (!environment.empty())
            for (size_t p = 0; p < pixels; ++p) {
                float* out = &data.rgba[(size_t(image.lights) * pixels + p) * 4];
                out[0] = environment[p].x;
                out[1] = environment[p].y;
                out[2] = environment[p].z;
                out[3] = image.glinty[p] ? 1.0f : 0.0f;
            }
        ++data.version;
    }
    RenderRequest final = request;
    final.settings.method = kReferenceMethodId;
    RenderResult result = session.render(final);
    result.stats["method"] = kReferenceMethodId;
    result.stats["reference"] = {{"seconds", image.seconds},
                                 {"threads", image.threads},
                                 {"lights", image.lights},
                                 {"facets_tested", image.facetsTested},
                                 {"environment_seconds", environmentSeconds},
                                 {"lobe", options.lobe == Lobe::Cone ? "cone" : "gaussian"},
                                 {"footprint", options.filter == FootprintFilter::Box ? "box" : "gaussian"},
                                 {"seed", options.seed}};
    return result;
}

std::string referenceCaption(const Scene& scene, const RenderSettings& settings) {
    registerReferenceMethod();
    const ReferenceOptions options = referenceOptions(settings);
    // Compact (a 256-pixel tile holds 32 characters of the caption font): lobe/footprint, seed, the material.
    std::string text = std::string(options.lobe == Lobe::Cone ? "cone" : "gauss") + "/" +
                       (options.filter == FootprintFilter::Box ? "box" : "gauss") + " s" + std::to_string(options.seed);
    for (const Material& m : scene.materials)
        if (m.glinty) {
            char material[64];
            std::snprintf(material, sizeof material, " %.2g/m2 g%.3g", double(m.glint.density), double(m.glint.angularSize));
            text += material;
            break;
        }
    return text;
}

}  // namespace glimmer::facets
