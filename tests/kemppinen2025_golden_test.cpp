// Golden images of the kemppinen2025 method (issue 5: "golden images" of GGX, Beckmann and each extension of
// Sec. 3.3.6) and of environment lighting with its importance sampler (--ibl glint-is, fixed sample count, so the
// Monte Carlo image is deterministic on llvmpipe). 256x256; references in tests/golden/ref/kemppinen2025_*.png,
// rewritten with GLIMMER_UPDATE_GOLDEN=1. The comparison tolerates one-pixel shifts of glints (support/golden.h).
#include <gtest/gtest.h>

#include "offscreen/offscreen.h"
#include "support/golden.h"

using namespace glimmer;

namespace {

struct GoldenCase {
    const char* name;
    const char* scene;
    std::vector<std::string> sets;   // --set assignments
    const char* environment;         // --env
    const char* ibl;
    int spp;
};

void PrintTo(const GoldenCase& c, std::ostream* os) { *os << c.name; }

class Kemppinen2025Golden : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(Kemppinen2025Golden, MatchesReference) {
    const GoldenCase& c = GetParam();
    RenderRequest request;
    request.scene = c.scene;
    request.width = request.height = 256;
    request.environment = c.environment;
    request.settings.method = "kemppinen2025";
    request.settings.ibl = c.ibl;
    for (const std::string& s : c.sets) request.settings.apply(s);
    request.spp = c.spp;
    RenderResult result = renderOffscreen(request);
    EXPECT_EQ(result.stats["counts"]["non_finite_values"].get<size_t>(), 0u);
    test::GoldenComparison comparison =
        test::compareWithGolden(std::string("kemppinen2025_") + c.name, result.display, result.width, result.height);
    EXPECT_TRUE(comparison.passed) << comparison.message;
}

INSTANTIATE_TEST_SUITE_P(
    Looks, Kemppinen2025Golden,
    ::testing::Values(GoldenCase{"sphere_ggx", "sphere", {}, "none", "prefiltered", 1},
                      GoldenCase{"sphere_beckmann", "sphere", {"material.ndf=beckmann"}, "none", "prefiltered", 1},
                      GoldenCase{"plane25", "plane25", {}, "none", "prefiltered", 1},
                      GoldenCase{"sphere_anisotropic", "sphere", {"glint_anisotropy=16"}, "none", "prefiltered", 1},
                      GoldenCase{"sphere_coloured", "sphere", {"color_variation=1", "density=3e5"}, "none",
                                 "prefiltered", 1},
                      GoldenCase{"sphere_triplanar", "sphere", {"triplanar=1"}, "none", "prefiltered", 1},
                      GoldenCase{"sphere_glint_is", "sphere", {"density=3e4", "micro_roughness=0.005"}, "procedural",
                                 "glint-is", 16}),
    [](const ::testing::TestParamInfo<GoldenCase>& info) { return std::string(info.param.name); });

}  // namespace
