// The foundation's guarantees: G-buffer UV derivatives against analytic values, lit radiance against the CPU
// BRDF, and backend equivalence.
#include <gtest/gtest.h>

#include <cmath>

#include "render/aov.h"
#include "reference/brdf_reference.h"
#include "offscreen/offscreen.h"
#include "scene/builtin_scenes.h"
#include "support/golden.h"

using namespace glimmer;

namespace {

// UV of the plane y = 0 seen through pixel coordinate (px, py) (GL convention, bottom row = 0, centres at +0.5).
glm::dvec2 planeUv(const Camera& camera, int width, int height, double px, double py) {
    Ray ray = cameraRay(camera, width, height, px, py);
    double t = -ray.origin.y / ray.direction.y;
    glm::dvec3 hit = ray.origin + t * ray.direction;
    return {hit.x + kPlaneUvOffset, hit.z + kPlaneUvOffset};
}

// Analytic derivative of the UV along screen x or y at (px, py): the exact Jacobian of the ray-plane
// intersection, evaluated by a central difference with a step small enough that truncation is < 1e-8 relative.
glm::dvec2 analyticDerivative(const Camera& camera, int width, int height, double px, double py, bool alongX) {
    const double e = 1e-3;
    glm::dvec2 step = alongX ? glm::dvec2(e, 0) : glm::dvec2(0, e);
    return (planeUv(camera, width, height, px + step.x, py + step.y) -
            planeUv(camera, width, height, px - step.x, py - step.y)) / (2.0 * e);
}

RenderResult renderAov(const std::string& scene, const std::string& aov, int size) {
    RenderRequest request;
    request.scene = scene;
    request.width = request.height = size;
    request.settings.debugView = findAov(aov).viewId;
    return renderOffscreen(request);
}

class PlaneDerivatives : public ::testing::TestWithParam<std::string> {};

TEST_P(PlaneDerivatives, MatchAnalyticValuesWithinOnePercent) {
    const int size = 256;
    Scene scene = makeBuiltinScene(GetParam());
    const Camera& camera = scene.cameras.front();
    RenderResult dx = renderAov(GetParam(), "duvdx", size);
    RenderResult dy = renderAov(GetParam(), "duvdy", size);
    RenderResult uv = renderAov(GetParam(), "uv", size);
    int checked = 0;
    double worst = 0.0;
    for (int y = 3; y < size; y += 17)
        for (int x = 5; x < size; x += 13) {
            size_t i = (size_t(y) * size + x) * 4;
            // The G-buffer takes fine derivatives: the difference across the 2x2 quad's pixel pair, i.e. the
            // derivative at the pair's shared edge (exact to second order).
            double edgeX = double(x & ~1) + 1.0, edgeY = double(y & ~1) + 1.0;
            glm::dvec2 expectX = analyticDerivative(camera, size, size, edgeX, y + 0.5, true);
            glm::dvec2 expectY = analyticDerivative(camera, size, size, x + 0.5, edgeY, false);
            glm::dvec2 gotX(dx.hdr[i], dx.hdr[i + 1]), gotY(dy.hdr[i], dy.hdr[i + 1]);
            double errX = glm::length(gotX - expectX) / glm::length(expectX);
            double errY = glm::length(gotY - expectY) / glm::length(expectY);
            worst = std::max({worst, errX, errY});
            EXPECT_LT(errX, 0.01) << "du/dx at pixel " << x << "," << y << ": " << gotX.x << "," << gotX.y
                                  << " expected " << expectX.x << "," << expectX.y;
            EXPECT_LT(errY, 0.01) << "du/dy at pixel " << x << "," << y;
            // The UV itself, 32-bit: within a hundredth of a pixel footprint.
            glm::dvec2 expectUv = planeUv(camera, size, size, x + 0.5, y + 0.5);
            EXPECT_LT(glm::length(glm::dvec2(uv.hdr[i], uv.hdr[i + 1]) - expectUv), 1e-2 * glm::length(expectX) + 2e-5);
            ++checked;
        }
    EXPECT_GT(checked, 200);
    std::printf("%s: worst relative derivative error %.2e over %d pixels\n", GetParam().c_str(), worst, checked);
}

INSTANTIATE_TEST_SUITE_P(Planes, PlaneDerivatives, ::testing::Values("plane90", "plane25"));

class PlaneRadiance : public ::testing::TestWithParam<std::string> {};

TEST_P(PlaneRadiance, MatchesCpuBrdfWithinOnePercent) {
    const int size = 256;
    const bool beckmann = GetParam() == "beckmann";
    RenderRequest request;
    request.scene = "plane90";
    request.width = request.height = size;
    for (const char* s : {"material.metallic=0.4", "material.alpha=0.25", "ambient=1"}) request.settings.apply(s);
    request.settings.apply(std::string("material.ndf=") + GetParam());
    request.environment = "none";   // the reference shades with the constant ambient, not image-based lighting
    RenderResult result = renderOffscreen(request);

    Scene scene = makeBuiltinScene("plane90");
    const Camera& camera = scene.cameras.front();
    const Light& light = scene.lights.front();
    const Material& material = scene.materials.front();
    reference::SurfacePoint surface;
    // The G-buffer stores base colour in 8 bits: quantize the reference the same way.
    surface.baseColor = glm::round(glm::dvec3(material.baseColor) * 255.0) / 255.0;
    surface.metallic = 0.4;
    surface.alpha = 0.25;
    surface.beckmann = beckmann;
    // Shading frame of the plane: t = +x, b = +z, n = +y.
    auto toShading = [](const glm::dvec3& v) { return glm::dvec3(v.x, v.z, v.y); };
    int checked = 0;
    double worst = 0.0;
    for (int y = 7; y < size; y += 19)
        for (int x = 4; x < size; x += 23) {
            Ray ray = cameraRay(camera, size, size, x + 0.5, y + 0.5);
            glm::dvec3 wo = toShading(-ray.direction);
            glm::dvec3 wi = toShading(glm::normalize(glm::dvec3(light.vector)));
            glm::dvec3 expected = reference::shadeDirectional(surface, wi, wo, glm::dvec3(light.color) * double(light.intensity),
                                                              glm::dvec3(scene.skyColor));
            size_t i = (size_t(y) * size + x) * 4;
            for (int c = 0; c < 3; ++c) {
                double err = std::abs(result.hdr[i + c] - expected[c]) / expected[c];
                worst = std::max(worst, err);
                EXPECT_LT(err, 0.01) << GetParam() << " pixel " << x << "," << y << " channel " << c << ": "
                                     << result.hdr[i + c] << " expected " << expected[c];
            }
            ++checked;
        }
    std::printf("%s: worst relative radiance error %.2e over %d pixels\n", GetParam().c_str(), worst, checked);
}

INSTANTIATE_TEST_SUITE_P(Ndfs, PlaneRadiance, ::testing::Values("ggx", "beckmann"));

TEST(Backends, EglAndOSMesaRenderTheSameImage) {
    RenderRequest request;
    request.scene = "sphere";
    request.width = request.height = 256;
    request.backend = Backend::Egl;
    RenderResult egl = renderOffscreen(request);
    request.backend = Backend::OSMesa;
    RenderResult osmesa = renderOffscreen(request);
    EXPECT_EQ(egl.stats["backend"], "egl");
    EXPECT_EQ(osmesa.stats["backend"], "osmesa");
    test::GoldenOptions exact;
    exact.channelThreshold = 1.0f / 255.0f;
    exact.shiftRadius = 0;
    exact.maxFailFraction = 0.0;
    exact.blockThreshold = 0.5f / 255.0f;
    test::GoldenComparison comparison = test::compareImages(egl.display, osmesa.display, 256, 256, exact);
    EXPECT_TRUE(comparison.passed) << comparison.message;
    double maxHdr = 0.0;
    for (size_t i = 0; i < egl.hdr.size(); ++i) maxHdr = std::max(maxHdr, double(std::abs(egl.hdr[i] - osmesa.hdr[i])));
    EXPECT_LT(maxHdr, 1e-4);
}

// One session (GL context, programs, environment) for every AOV, as the window switches its debug view; each
// AOV is still a full render of its own whose every value is counted.
TEST(Output, NoNonFiniteValuesInAnyAov) {
    RenderRequest request;
    request.scene = "heightmap25";
    request.width = request.height = 64;
    OffscreenSession session(request);
    for (const AovInfo& aov : aovTable()) {
        request.settings.debugView = aov.viewId;
        RenderResult r = session.render(request);
        EXPECT_EQ(r.stats["counts"]["non_finite_values"].get<size_t>(), 0u) << aov.name;
    }
}

}  // namespace
