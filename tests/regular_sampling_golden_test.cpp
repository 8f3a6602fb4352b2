// Golden images of the issue-7 IBL modes (tests/support/golden.h; GLIMMER_UPDATE_GOLDEN=1 rewrites the references):
// glossy spheres (isotropic and anisotropic Kurt lobes, regular and fis) under the procedural sky, and the atrium's
// court camera with the regular mode on every material. Also the modes' bad-input errors.
#include <gtest/gtest.h>

#include "core/error.h"
#include "environment/ibl/ibl_modes.h"
#include "offscreen/offscreen.h"
#include "render/settings.h"
#include "support/golden.h"

namespace glimmer {
namespace {

RenderResult renderWith(const std::string& scene, const std::string& ibl, const std::vector<std::string>& sets,
                        int size) {
    RenderRequest r;
    r.scene = scene;
    r.width = r.height = size;
    r.settings.ibl = ibl;
    for (const std::string& s : sets) r.settings.apply(s);
    return renderOffscreen(r);
}

void expectGolden(const std::string& name, const RenderResult& result) {
    test::GoldenComparison c = test::compareWithGolden(name, result.display, result.width, result.height);
    EXPECT_TRUE(c.passed) << c.message;
}

TEST(RegularSamplingGolden, GlossySpheres) {
    const std::vector<std::string> metal = {"material.metallic=1", "material.alpha=0.15"};
    std::vector<std::string> aniso = metal;
    aniso.push_back("ibl.mx=0.2");
    aniso.push_back("ibl.my=0.075");
    expectGolden("regular_sphere_isotropic", renderWith("sphere", "regular", metal, 128));
    expectGolden("regular_sphere_anisotropic", renderWith("sphere", "regular", aniso, 128));
    expectGolden("fis_sphere_anisotropic", renderWith("sphere", "fis", aniso, 128));
}

TEST(RegularSamplingGolden, AtriumCourt) {
    RenderRequest r;
    r.scene = "atrium";
    r.camera = "court";
    r.width = r.height = 128;
    r.settings.ibl = "regular";
    expectGolden("regular_atrium_court", renderOffscreen(r));
}

TEST(RegularSamplingGolden, BadParametersAreOneLineUsageErrors) {
    RenderSettings settings;
    settings.ibl = "regular";
    EXPECT_THROW(settings.apply("ibl.xi0=1.5"), UsageError);
    EXPECT_THROW(settings.apply("ibl.samples=0"), UsageError);
    EXPECT_THROW(settings.apply("ibl.ring_rule=spiral"), UsageError);
    EXPECT_THROW(settings.apply("ibl.pyramid=gauss8"), UsageError);
    settings.ibl = "fis";
    EXPECT_THROW(settings.apply("ibl.xi0=0.2"), UsageError) << "fis has no xi0";
    settings.apply("ibl.pyramid=gauss6");
}

// A mode's defaults are its paper's method: regular sampling reads the 6x6 Gaussian pyramid of Sec. 3 (the one its
// Sec. 8 evaluation uses); fis is Colbert & Krivanek's filtered importance sampling, which reads the plain
// (box-filtered) mip chain of the map.
TEST(RegularSamplingGolden, DefaultPyramidsFollowThePapers) {
    auto defaultPyramid = [](const std::string& mode) {
        for (const ParamSpec& spec : findIblMode(mode).params)
            if (spec.name == "pyramid") return spec.choices.at(size_t(spec.defaultValue));
        return std::string("(none)");
    };
    EXPECT_EQ(defaultPyramid("regular"), "gauss6");
    EXPECT_EQ(defaultPyramid("fis"), "source");
}

}  // namespace
}  // namespace glimmer
