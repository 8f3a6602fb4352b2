// Hot reload of a user glint method in the running window (issue 15), under xvfb-run: the window renders the
// glint AOV (D of the first light) of a small user method; a shell loop edits the file between the screenshots
// an input script takes. Checked: the first version renders D = gain D_smooth with --set gain=2; a header edit
// that adds a parameter is read without a restart, keeps gain=2 and feeds the new parameter's default to the
// shader; a broken body keeps the last good program and logs file:line; an unparsable header keeps it too and
// names its line. Skipped where xvfb-run is absent.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/image_io.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(Window, Window);

namespace glimmer {
namespace {
namespace fs = std::filesystem;

bool haveXvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::trunc) << text; }

std::string readAll(const fs::path& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

const char* kVersion1 = R"(/* glimmer-method
name: hot_test
citation: tests/window_user_method_test.cpp
param: gain = 1 in [0, 4]: multiplies the smooth NDF
*/
#define glintD smoothGlintD
#include "glints/smooth.glsl"
)";

// The method body shared by the versions (smooth.glsl's glintD renamed, then a new one).
const char* kBody1 = R"(#undef glintD
float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) { return P_GAIN * D_smooth(h, s.alpha, s.ndf); }
)";

TEST(Window, UserMethodHotReloadHeaderBodyAndErrors) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    fs::path dir = test::makeTempDir("window-user-method");
    fs::path method = dir / "hot_test.glsl", v2 = dir / "v2.glsl", v3 = dir / "v3.glsl", v4 = dir / "v4.glsl";
    // smooth.glsl defines glintD itself: it is renamed on the way in (the pattern of content/methods/).
    std::string v1Text = kVersion1;
    write(method, v1Text + kBody1);
    // v2: a new parameter in the header, used by the body.
    std::string v2Text = v1Text;
    v2Text.insert(v2Text.find("*/"), "param: offset = 0.25 in [0, 1]: added to D\n");
    std::string body2 = R"(#undef glintD
float glintD(GlintPixel px, GlintSurface s, vec3 h, vec3 wi, vec3 wo) { return P_GAIN * D_smooth(h, s.alpha, s.ndf) + P_OFFSET; }
)";
    write(v2, v2Text + body2);
    // v3: the body does not compile (line counted below); v4: the header does not parse (line 5).
    std::string v3Text = v2Text + body2 + "this is not glsl;\n";
    int brokenLine = int(std::count(v3Text.begin(), v3Text.end(), '\n'));
    write(v3, v3Text);
    std::string v4Text = v2Text;
    v4Text.insert(v4Text.find("param: offset"), "param: broken = 9 in [0, 1]: out of range\n");
    write(v4, v4Text + body2);

    fs::path script = dir / "script.txt";
    fs::path a = dir / "a.exr", b = dir / "b.exr", c = dir / "c.exr", d = dir / "d.exr", log = dir / "view.err";
    write(script, "1 screenshot " + a.string() + "\n4.5 screenshot " + b.string() + "\n8 screenshot " + c.string() +
                      "\n11.5 screenshot " + d.string() + "\n12 quit\n");
    auto waitFor = [](const fs::path& f) { return "while [ ! -f " + f.string() + " ]; do sleep 0.1; done; "; };
    std::string view = std::string(GLIMMER_EXECUTABLE) + " view --scene plane90 --size 64x64 --aov glint --no-vsync" +
                       " --render-scale 1 --target-fps 0 --method-file " + method.string() +
                       " --set hot_test.gain=2 --input-script " + script.string();
    std::string command = view + " > /dev/null 2> " + log.string() + " & pid=$!; " + waitFor(a) + "cp " + v2.string() +
                          " " + method.string() + "; " + waitFor(b) + "cp " + v3.string() + " " + method.string() +
                          "; " + waitFor(c) + "cp " + v4.string() + " " + method.string() + "; wait $pid";
    ASSERT_EQ(test::runUnderXvfb(command), 0) << readAll(log);
    ASSERT_TRUE(fs::exists(d)) << readAll(log);
    ImageF first = readImage(a), second = readImage(b), third = readImage(c), fourth = readImage(d);
    ASSERT_EQ(first.width, 64);

    // Reference D_smooth from glimmer render (same view, smooth method, glint AOV).
    fs::path smooth = dir / "smooth.exr";
    test::ProcessResult render = test::runGlimmer({"render", "--scene", "plane90", "--size", "64x64", "--method",
                                                   "smooth", "--aov", "glint", "--out", smooth.string()});
    ASSERT_EQ(render.exitCode, 0) << render.err;
    ImageF reference = readImage(smooth);
    int compared = 0, wrong1 = 0, wrong2 = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            float ds = reference.at(x, y, 0);
            if (!(ds > 1e-3f)) continue;
            ++compared;
            wrong1 += std::abs(first.at(x, y, 0) - 2.0f * ds) > 1e-4f * ds + 1e-6f;          // gain=2 from --set
            wrong2 += std::abs(second.at(x, y, 0) - (2.0f * ds + 0.25f)) > 1e-4f * ds + 1e-5f;  // gain kept, new offset
        }
    EXPECT_GT(compared, 1000);
    EXPECT_EQ(wrong1, 0);
    EXPECT_EQ(wrong2, 0) << "the header edit must reach the shader with gain kept at 2";
    // Broken body, then broken header: the last good program (v2) keeps running.
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            ASSERT_EQ(third.at(x, y, 0), second.at(x, y, 0));
            ASSERT_EQ(fourth.at(x, y, 0), second.at(x, y, 0));
        }
    std::string messages = readAll(log);
    EXPECT_NE(messages.find("method hot_test: header read (2 parameters)"), std::string::npos) << messages;
    EXPECT_NE(messages.find("hot_test.glsl:" + std::to_string(brokenLine) + ":"), std::string::npos) << messages;
    EXPECT_NE(messages.find("hot_test.glsl:5: parameter 'broken': default 9 is outside [0, 1]"), std::string::npos)
        << messages;
}

}  // namespace
}  // namespace glimmer
