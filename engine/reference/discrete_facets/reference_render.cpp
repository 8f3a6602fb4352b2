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
#include "glints/methods.h"
#include "render/aov.h"

namespace glimmer::facets {

namespace {

// What the CPU computed for the frame the `reference` method renders next: per pixel, one RGBA32F layer per light
// (rgb D_est, a 1 where evaluated). Shared between renderReference() and the method's GPU resources.
struct ReferenceFrameData {
    std::mutex mutex;
    int width = 0, height = 0, layers = 0;
    std::vector<float> rgba;   // layer-major, rows bottom-up
    uint64_t version = 0;
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
        glBindTextureUnit(UNIT_METHOD_FIRST, texture_.id());
    }

private:
    gl::Texture texture_;
    uint64_t uploaded_ = ~uint64_t(0);
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
                        {"threads", 0.0f, 0.0f, 256.0f, "CPU threads (0 = every hardware thread)", {}, true}}};
    method.createResources = [] { return std::make_unique<ReferenceResources>(); };
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
                             material = renderAov(session, r, "material");
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
        }
    return surface;
}

RenderResult renderReference(OffscreenSession& session, const RenderRequest& request) {
    if (int(request.settings.common_("aa")) != 0)
        throw UsageError("--method reference: needs aa=0 (it counts the facets of each pixel's own footprint once)");
    if (request.renderScale != 1.0f)
        throw UsageError("--method reference: needs --render-scale 1 (the facets are counted per render pixel)");
    registerReferenceMethod();
    const ReferenceOptions options = referenceOptions(request.settings);
    SurfaceImage surface = captureSurface(session, request);
    const Scene& scene = session.scene();
    ReferenceImage image = evaluateLights(surface, scene.materials, scene.lights, options);
    log::info("reference: ", image.width, "x", image.height, ", ", image.lights, " light(s), ", image.threads,
              " thread(s): ", image.seconds, " s, ", image.facetsTested, " facets tested");
    {
        ReferenceFrameData& data = frameData();
        std::lock_guard<std::mutex> lock(data.mutex);
        data.width = image.width;
        data.height = image.height;
        data.layers = std::max(image.lights, 1);
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
                                 {"lobe", options.lobe == Lobe::Cone ? "cone" : "gaussian"},
                                 {"footprint", options.filter == FootprintFilter::Box ? "box" : "gaussian"},
                                 {"seed", options.seed}};
    return result;
}

std::string referenceCaption(const Scene& scene, const RenderSettings& settings) {
    registerReferenceMethod();
    const ReferenceOptions options = referenceOptions(settings);
    std::string text = std::string(options.lobe == Lobe::Cone ? "cone" : "gaussian lobe") + ", " +
                       (options.filter == FootprintFilter::Box ? "box" : "gaussian") + " footprint, seed " +
                       std::to_string(options.seed);
    for (const Material& m : scene.materials)
        if (m.glinty) {
            char material[96];
            std::snprintf(material, sizeof material, "; %.3g /m2, gamma %.3g", double(m.glint.density),
                          double(m.glint.angularSize));
            text += material;
            break;
        }
    return text;
}

}  // namespace glimmer::facets
