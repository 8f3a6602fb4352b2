// User glint methods (issue 15): the header block of a method file (good headers and every kind of bad one, each
// named by its line), loading through the real GL pipeline (the example with bilinear blending renders exactly
// like the built-in deliot2023 it includes), the command line (--method-file, file: in --compare, --set,
// --list-params, a scene file's methodFiles), and check-method on the example (passes) and on a deliberately
// broken method (fails the furnace rule, and only that). The window's hot reload of a user method is
// Window.UserMethodHotReload in tests/window_user_method_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "checks/method_checks.h"
#include "core/files.h"
#include "glints/glint_mapping.h"
#include "glints/user/user_methods.h"
#include "offscreen/offscreen.h"
#include "render/aov.h"
#include "render/settings.h"
#include "support/measure.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(UserMethod, GlContext);
GLIMMER_SUITE_NEEDS(UserMethodCheck, Process);

namespace glimmer {
namespace {
namespace fs = std::filesystem;

fs::path examplePath() { return fs::path(GLIMMER_SOURCE_DIR) / "content" / "methods" / "deliot2023_smoothstep.glsl"; }
fs::path brokenPath() { return fs::path(GLIMMER_TEST_DIR) / "data" / "methods" / "clamped_glints.glsl"; }

const char* kGoodHeader = R"(// a comment before the header
/* glimmer-method
name:      my_glints
citation:  nobody 2025, Eq. 1
 * title:  My glints: a title with: colons
resources: deliot2023
# a comment line inside the header
param: log_density = 16 in [0, 50]: natural log of the density: per m^2
param: roughness = 0.01 in [0.001, 1] log: micro roughness
param: steps = 4 in [1, 16] int: loop steps
param: blend = smooth in {linear, smooth, cubic}: how cells blend
converge:  log_density=40, blend=linear
map: log_density = ln(density_per_uv) - steps^2/2
map: roughness = 2 (angular_size)^2 alpha^-2
map: steps = 3
*/
float glintD() { return 1.0; }
)";

TEST(UserMethodHeader, GoodHeaderGivesTheTableEntry) {
    GlintMethod m = parseUserMethodHeader(kGoodHeader, "good.glsl");
    EXPECT_EQ(m.id, "my_glints");
    EXPECT_EQ(m.title, "My glints: a title with: colons");
    EXPECT_EQ(m.citation, "nobody 2025, Eq. 1");
    EXPECT_EQ(m.resourcesFrom, "deliot2023");
    EXPECT_TRUE(bool(m.createResources));
    ASSERT_EQ(m.params.size(), 4u);
    EXPECT_EQ(m.params[0].name, "log_density");
    EXPECT_EQ(m.params[0].defaultValue, 16.0f);
    EXPECT_EQ(m.params[0].minValue, 0.0f);
    EXPECT_EQ(m.params[0].maxValue, 50.0f);
    EXPECT_EQ(m.params[0].meaning, "natural log of the density: per m^2");
    EXPECT_TRUE(m.params[1].logScale);
    EXPECT_FALSE(m.params[1].integer);
    EXPECT_TRUE(m.params[2].integer);
    EXPECT_EQ(m.params[3].choices, (std::vector<std::string>{"linear", "smooth", "cubic"}));
    EXPECT_EQ(m.params[3].defaultValue, 1.0f);
    EXPECT_EQ(m.params[3].maxValue, 2.0f);
    EXPECT_EQ(m.convergence.at("log_density"), 40.0f);
    EXPECT_EQ(m.convergence.at("blend"), 0.0f);
    // map lines: the glint material's quantities, in the form --list-params prints.
    ASSERT_EQ(m.materialMapping.size(), 3u);
    EXPECT_EQ(mappingFormula(m.materialMapping[0]), "log_density = ln(density_per_uv) - steps^2/2");
    EXPECT_TRUE(m.materialMapping[0].log);
    EXPECT_EQ(m.materialMapping[0].minusHalfSquareOf, "steps");
    EXPECT_EQ(m.materialMapping[1].quantity, GlintQuantity::AngularSize);
    EXPECT_EQ(m.materialMapping[1].scale, 2.0f);
    EXPECT_EQ(m.materialMapping[1].power, 2.0f);
    EXPECT_EQ(m.materialMapping[1].alphaPower, -2.0f);
    EXPECT_EQ(mappingFormula(m.materialMapping[1]), "roughness = 2 (angular_size)^2 alpha^-2");
    // A number alone is a constant on every material (issue 36: switching a knob off), printed back as such.
    EXPECT_EQ(m.materialMapping[2].power, 0.0f);
    EXPECT_EQ(mappingFormula(m.materialMapping[2]), "steps = 3");
    Material any;
    any.glint.density = 0.0f;   // q^0 is 1 even for a zero quantity
    EXPECT_EQ(mappedValue(m.materialMapping[2], any), 3.0f);
    // The same P_<NAME> block as the built-ins (outside the lighting pass P_ reads the shared values PS_).
    std::string glsl = methodParamsGlsl(m);
    EXPECT_NE(glsl.find("#define PS_LOG_DENSITY u_methodParams[0].x"), std::string::npos) << glsl;
    EXPECT_NE(glsl.find("#define P_LOG_DENSITY PS_LOG_DENSITY"), std::string::npos) << glsl;
    EXPECT_NE(glsl.find("#define PS_BLEND u_methodParams[0].w"), std::string::npos) << glsl;
    // In the lighting pass P_ reads the pixel's material's row (per-material parameters, glint_mapping.h).
    std::string lighting = methodParamsGlsl(m, true);
    EXPECT_NE(lighting.find("#define P_LOG_DENSITY u_materialMethodParams[g_glintMaterial * 16 + 0].x"),
              std::string::npos) << lighting;
    // Defaults only: title falls back to the name, no resources.
    GlintMethod small = parseUserMethodHeader("/* glimmer-method\nname: tiny\ncitation: x\n*/\n", "tiny.glsl");
    EXPECT_EQ(small.title, "tiny");
    EXPECT_TRUE(small.params.empty());
    EXPECT_FALSE(bool(small.createResources));
}

struct BadHeader {
    const char* text;
    int line;
    const char* message;
};

TEST(UserMethodHeader, EveryBadHeaderIsAnErrorNamingItsLine) {
    const BadHeader cases[] = {
        {"float x;\n", 1, "no header block"},
        {"\n/* glimmer-method\nname: a\ncitation: c\n", 2, "not closed"},
        {"/* glimmer-method\ncitation: c\n*/\n", 1, "has no 'name'"},
        {"/* glimmer-method\nname: a\n*/\n", 1, "has no 'citation'"},
        {"/* glimmer-method\nname: Bad-Name\ncitation: c\n*/\n", 2, "lower-case"},
        {"/* glimmer-method\nname: a\nname: b\ncitation: c\n*/\n", 3, "given twice"},
        {"/* glimmer-method\nname: a\ncitation: c\ncolour: red\n*/\n", 4, "unknown key 'colour'"},
        {"/* glimmer-method\nname: a\ncitation: c\njust words\n*/\n", 4, "expected 'key: value'"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x 1 [0, 2]: m\n*/\n", 4, "expected 'param: NAME = DEFAULT"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 3 in [0, 2]: m\n*/\n", 4, "outside [0, 2]"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [2, 0]: m\n*/\n", 4, "minimum must be below"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = one in [0, 2]: m\n*/\n", 4, "is not a number"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [0, inf]: m\n*/\n", 4, "two finite numbers"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [0, 2] fast: m\n*/\n", 4, "unknown flag 'fast'"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1.5 in [0, 2] int: m\n*/\n", 4, "whole default"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [0, 2]:\n*/\n", 4, "has no meaning"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [0, 2]: m\nparam: X = 1 in [0, 2]: m\n*/\n", 5,
         "must be lower-case"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [0, 2]: m\nparam: x = 1 in [0, 2]: m\n*/\n", 5,
         "declared twice"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: e = c in {a, b}: m\n*/\n", 4, "not one of its choices"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: e = a in {a}: m\n*/\n", 4, "at least two choices"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: e = a in {a, a}: m\n*/\n", 4, "listed twice"},
        {"/* glimmer-method\nname: a\ncitation: c\nconverge: y=2\nparam: x = 1 in [0, 2]: m\n*/\n", 4,
         "'y' is not a parameter"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [0, 2]: m\nconverge: x=5\n*/\n", 5, "outside"},
        {"/* glimmer-method\nname: a\ncitation: c\nmap: y = density_per_uv\n*/\n", 4, "'y' is not a parameter"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [0, 2]: m\nmap: x = 2 weight\n*/\n", 5,
         "'weight' is not a quantity"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [0, 2]: m\nmap: x = alpha\nmap: x = alpha\n*/\n", 6,
         "mapped twice"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [0, 2]: m\nmap: x = ln(alpha\n*/\n", 5,
         "closing ')'"},
        {"/* glimmer-method\nname: a\ncitation: c\nparam: x = 1 in [0, 2]: m\nmap: x = ln(alpha) - s^2/2\n*/\n", 5,
         "'s' (in '- NAME^2/2') is not a parameter"},
        {"/* glimmer-method\nname: a\ncitation: c\nresources: nowhere\n*/\n", 4, "not a built-in method"},
        {"/* glimmer-method\nname: a\ncitation: c\nresources: zirr2016\n*/\n", 4, "has no GPU resources"},
        {"/* glimmer-method\nname: a\ncitation: c */ float x;\n", 3, "code after the header"},
    };
    for (const BadHeader& c : cases) {
        try {
            parseUserMethodHeader(c.text, "bad.glsl");
            ADD_FAILURE() << "accepted:\n" << c.text;
        } catch (const Error& e) {
            std::string what = e.what();
            EXPECT_EQ(what.rfind("bad.glsl:" + std::to_string(c.line) + ": ", 0), 0u) << what << "\nfor:\n" << c.text;
            EXPECT_NE(what.find(c.message), std::string::npos) << what;
        }
    }
}

TEST(UserMethodHeader, ExampleRegistersAndIsListedLikeABuiltIn) {
    std::string id = resolveGlintMethod("file:" + examplePath().string());
    EXPECT_EQ(id, "deliot2023_smoothstep");
    EXPECT_EQ(resolveGlintMethod("file:" + examplePath().string()), id);   // loaded once
    const GlintMethod& m = findGlintMethod(id);
    EXPECT_TRUE(m.isUserMethod());
    EXPECT_EQ(m.sourceFile, fs::canonical(examplePath()));
    EXPECT_EQ(m.convergence.at("log_density"), 40.0f);
    // Its map lines are the built-in's mapping: a glinty material gets the same parameter values from both.
    Material glinty;
    glinty.glinty = true;
    glinty.alpha = 0.3f;
    glinty.glint.density = 4e6f;
    glinty.glint.angularSize = 0.02f;
    const GlintMethod& builtin = findGlintMethod("deliot2023");
    for (const char* name : {"log_density", "microfacet_roughness"})   // log_density with its - sigma^2/2
        EXPECT_FLOAT_EQ(materialParams(m, glinty, {}).at(name), materialParams(builtin, glinty, {}).at(name)) << name;
    std::string listing = describeParams();
    EXPECT_NE(listing.find("deliot2023_smoothstep.angular_blend"), std::string::npos);
    RenderSettings s;
    s.method = id;
    s.apply("angular_blend=bilinear");
    EXPECT_EQ(s.methods[id]["angular_blend"], 0.0f);
    EXPECT_THROW(s.apply("deliot2023_smoothstep.angular_blend=cubic"), UsageError);
    // A second file may not take a name in use.
    std::string dir = test::makeTempDir("user-method-clash");
    std::ofstream(dir + "/clash.glsl") << "/* glimmer-method\nname: deliot2023\ncitation: c\n*/\n";
    EXPECT_THROW(loadUserMethodFile(dir + "/clash.glsl"), Error);
    // Values carried across a header change: kept when the name exists, clamped into the new range.
    GlintMethod changed = m;
    changed.params.resize(2);
    changed.params[0].maxValue = 20.0f;
    ParamValues kept = carryParamValues({{"log_density", 30.0f}, {"angular_blend", 1.0f}, {"gone", 3.0f}}, changed);
    EXPECT_EQ(kept.size(), 1u);
    EXPECT_EQ(kept.at("log_density"), 20.0f);
}

// Through the real pipeline: with angular_blend=bilinear the example is deliot2023 (it includes the built-in and
// replaces only the blend weights), so the renders agree to the bit; smoothstep changes the glints, not the mean.
TEST(UserMethod, ExampleRendersAndBilinearBlendIsTheBuiltIn) {
    std::string id = loadUserMethodFile(examplePath());
    RenderRequest request;
    request.scene = "plane25";
    request.environment = "none";
    request.width = request.height = 96;
    request.settings.method = "deliot2023";
    request.settings.debugView = findAov("glint").viewId;
    OffscreenSession session(request);
    std::vector<float> builtin = session.render(request).hdr;
    RenderRequest user = request;
    user.settings.method = id;
    user.settings.methods[id]["angular_blend"] = 0.0f;
    std::vector<float> bilinear = session.render(user).hdr;
    user.settings.methods[id]["angular_blend"] = 1.0f;
    RenderResult smoothstep = session.render(user);
    EXPECT_EQ(builtin, bilinear);
    size_t differ = 0, lit = 0;
    for (size_t i = 0; i < builtin.size(); i += 4) {
        differ += builtin[i] != smoothstep.hdr[i];
        lit += builtin[i] > 0.0f;
    }
    EXPECT_GT(lit, 100u);
    EXPECT_GT(differ, lit / 4) << "smoothstep blending must change the glints";
    EXPECT_EQ(smoothstep.stats["method"], id);
}

TEST(UserMethod, CommandLineLoadsCompareListAndSceneKey) {
    fs::path dir = test::makeTempDir("user-method-cli");
    std::string example = examplePath().string();
    test::ProcessResult list = test::runGlimmer({"render", "--method-file", example, "--list-params"});
    EXPECT_EQ(list.exitCode, 0) << list.err;
    EXPECT_NE(list.out.find("Method deliot2023_smoothstep"), std::string::npos);
    EXPECT_NE(list.out.find("deliot2023_smoothstep.angular_blend"), std::string::npos);

    fs::path grid = fs::path(dir) / "grid.png";
    test::ProcessResult compare = test::runGlimmer({"render", "--scene", "plane90", "--env", "none", "--size", "48x48", "--compare",
                                                    "deliot2023,file:" + example, "--out", grid.string()});
    EXPECT_EQ(compare.exitCode, 0) << compare.err;
    EXPECT_TRUE(fs::exists(grid));

    // --method-file selects the method; --set names its parameters like a built-in's.
    fs::path out = fs::path(dir) / "one.png";
    test::ProcessResult one = test::runGlimmer({"render", "--scene", "plane90", "--env", "none", "--size", "32x32", "--method-file",
                                                example, "--set", "angular_blend=bilinear", "--stats", "--out",
                                                out.string()});
    EXPECT_EQ(one.exitCode, 0) << one.err;
    EXPECT_NE(one.out.find("\"method\":\"deliot2023_smoothstep\""), std::string::npos) << one.out;

    // A scene file's methodFiles: its first method is the default.
    fs::path scene = fs::path(dir) / "scene.json";
    std::ofstream(scene) << "{\"base\": \"plane90\", \"methodFiles\": [\"" << example << "\"]}";
    test::ProcessResult fromScene =
        test::runGlimmer({"render", "--scene", scene.string(), "--env", "none", "--size", "32x32", "--stats", "--out",
                          out.string()});
    EXPECT_EQ(fromScene.exitCode, 0) << fromScene.err;
    EXPECT_NE(fromScene.out.find("\"method\":\"deliot2023_smoothstep\""), std::string::npos) << fromScene.out;

    // A bad header: one line naming file:line, exit 1; a shader error in the file: file:line too.
    fs::path bad = fs::path(dir) / "bad.glsl";
    std::ofstream(bad) << "/* glimmer-method\nname: bad\ncitation: c\nparam: x = 5 in [0, 2]: m\n*/\n";
    test::ProcessResult badRun = test::runGlimmer({"render", "--method-file", bad.string(), "--out", out.string()});
    EXPECT_EQ(badRun.exitCode, 1);
    EXPECT_NE(badRun.err.find("bad.glsl:4: parameter 'x': default 5 is outside [0, 2]"), std::string::npos) << badRun.err;
    EXPECT_EQ(std::count(badRun.err.begin(), badRun.err.end(), '\n'), 1) << badRun.err;
    fs::path broken = fs::path(dir) / "broken.glsl";
    std::ofstream(broken) << "/* glimmer-method\nname: broken\ncitation: c\n*/\n#include \"glints/smooth.glsl\"\n"
                             "this is not glsl;\n";
    test::ProcessResult brokenRun =
        test::runGlimmer({"render", "--size", "16x16", "--env", "none", "--method-file", broken.string(), "--out", out.string()});
    EXPECT_EQ(brokenRun.exitCode, 1);
    EXPECT_NE(brokenRun.err.find("broken.glsl:6:"), std::string::npos) << brokenRun.err;
    test::ProcessResult unknown = test::runGlimmer({"render", "--compare", "deliot2023,nope", "--out", out.string()});
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("file:PATH.glsl"), std::string::npos) << unknown.err;
}

// check-method on the example: every rule passes. Convergence, furnace and finite are deterministic; the timing
// rules (cost, constant-time) run with GLIMMER_MEASURE=1 only: they cost four more sessions and depend on the
// load of a shared CI machine.
TEST(UserMethodCheck, ExamplePassesEveryRule) {
    std::string id = loadUserMethodFile(examplePath());
    checks::CheckOptions options;
    options.size = 96;
    options.timingSize = 128;
    options.timingFrames = 3;
    bool timing = test::fullMeasurement();
    if (!timing) options.rules = {"convergence", "furnace", "finite"};
    checks::CheckReport report = checks::checkMethod(id, options);
    std::string table = checks::formatTable(report);
    std::printf("%s", table.c_str());
    ASSERT_EQ(report.results.size(), timing ? 5u : 3u);
    EXPECT_TRUE(report.passed()) << table;
}

// The broken method (D clamped to 4 D_smooth) converges and stays finite but loses energy at glinty densities:
// check-method must exit 1 naming the furnace rule, and no other deterministic rule.
TEST(UserMethodCheck, BrokenMethodFailsTheFurnaceRule) {
    test::ProcessResult run = test::runGlimmer({"check-method", brokenPath().string(), "--rules",
                                                "convergence,furnace,finite", "--size", "64"});
    EXPECT_EQ(run.exitCode, 1) << run.out << run.err;
    EXPECT_NE(run.err.find("rule failed: furnace\n"), std::string::npos) << run.err;
    EXPECT_NE(run.out.find("furnace        FAIL"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("convergence    pass"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("finite         pass"), std::string::npos) << run.out;
    test::ProcessResult missing = test::runGlimmer({"check-method", "/nonexistent/x.glsl"});
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_NE(missing.err.find("/nonexistent/x.glsl: method file not found"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace glimmer
