// The walkthrough window played like a game, under xvfb with a scripted input (`view --input-script`, timed key
// events replayed at exact times, so the results do not depend on the machine's load): a held key moves by
// speed x time, a tap between frames moves, walking into a wall stops at it, a fall lands on the floor, and the
// panel is drawn at 960x540, 1280x720 and 1920x1080. Skipped where xvfb-run is absent.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/image_io.h"
#include "support/golden.h"
#include "support/process.h"
#include "support/test_needs.h"

// What these suites need beyond the CPU (their ctest label: tests/support/test_needs.h).
GLIMMER_SUITE_NEEDS(WindowWalk, Window);

namespace glimmer {
namespace {
namespace fs = std::filesystem;

bool haveXvfb() { return std::system("command -v xvfb-run > /dev/null 2>&1") == 0; }

struct Report {
    double time;
    glm::vec3 position;
    std::string mode;
    float speed;
};

// Runs `view ARGS --input-script` with `script` and returns its print lines.
std::vector<Report> playScript(const std::string& name, const std::string& args, const std::string& script) {
    fs::path dir = test::testOutputDir() / "window-walk";
    fs::create_directories(dir);
    fs::path scriptFile = dir / (name + ".script"), out = dir / (name + ".out");
    std::ofstream(scriptFile) << script;
    int code = test::runUnderXvfb(std::string(GLIMMER_EXECUTABLE) + " view " + args + " --input-script " +
                                  scriptFile.string() + " > " + out.string() + " 2> " + (dir / (name + ".err")).string());
    EXPECT_EQ(code, 0) << name;
    std::vector<Report> reports;
    std::ifstream in(out);
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string t, p, m, s;
        Report r;
        if (words >> t >> r.time >> p >> r.position.x >> r.position.y >> r.position.z >> m >> r.mode >> s >> r.speed)
            reports.push_back(r);
    }
    return reports;
}

TEST(WindowWalk, AHeldKeyMovesSpeedTimesTimeAndATapMoves) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    auto r = playScript("held", "--scene sphere --env none --method smooth --size 96x54",
                        "0.1 print\n0.3 down w\n2.3 up w\n2.5 print\n2.6 press w\n3.0 print\n3.1 quit\n");
    ASSERT_EQ(r.size(), 3u);
    EXPECT_EQ(r[0].mode, "fly");  // the sphere's camera does not stand on a floor
    double expected = r[0].speed * 2.0;
    EXPECT_NEAR(glm::length(r[1].position - r[0].position), expected, 0.1 * expected);
    float tap = glm::length(r[2].position - r[1].position);
    EXPECT_GT(tap, 0.0f);  // pressed and released between two frames: still a step
    EXPECT_LE(tap, r[0].speed * 0.11f);
}

// The atrium's entrance camera stands on the floor (walking); behind it the entrance wall is at x = 15.5.
TEST(WindowWalk, WalkingIntoAWallStopsAtItAndAFallLandsOnTheFloor) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    auto r = playScript("wall", "--scene atrium --env none --method smooth --size 96x54",
                        "0.1 print\n0.2 look 1256.637 0\n0.3 down w\n3.3 up w\n3.4 print\n"  // 5.4 m towards the wall
                        "3.5 press f\n3.6 down e\n4.6 up e\n4.7 print\n4.8 press f\n6.8 print\n6.9 quit\n");
    ASSERT_EQ(r.size(), 4u);
    EXPECT_EQ(r[0].mode, "walk");
    EXPECT_NEAR(r[0].position.y, 1.7f, 0.01f);
    EXPECT_GT(r[1].position.x, r[0].position.x + 0.3f);  // it walked up to the wall ...
    EXPECT_LE(r[1].position.x, 15.5f - 0.3f + 0.01f);    // ... and stopped a capsule radius before it
    EXPECT_NEAR(r[1].position.y, r[0].position.y, 0.01f);
    EXPECT_EQ(r[2].mode, "fly");
    EXPECT_NEAR(r[2].position.y, r[1].position.y + r[0].speed * 1.0f, 0.1f * r[0].speed);  // flew up 1 s
    EXPECT_EQ(r[3].mode, "walk");
    EXPECT_NEAR(r[3].position.y, r[1].position.y, 0.01f);  // fell back onto the floor
}

// Scene switching from the panel with the keyboard: focus the "Scene, camera, window" header (fourth focusable
// row with smooth, which has no parameters: after the method selector, and the load button of content/methods'),
// open it (the Method section closes, so the focus index now lands one row below the scene selector: up), step the scene selector: the atrium (last built-in)
// wraps to plane90, whose camera looks down from 2 m and flies.
TEST(WindowWalk, ThePanelSwitchesScenes) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    // Ambient occlusion and shadows off: the sky bake and the shadow maps make the first atrium frame seconds
    // long on a loaded llvmpipe machine, and the timed presses would then reach the window in one frame.
    auto r = playScript("scene",
                        "--scene atrium --env none --method smooth --size 320x180 --set ao.enabled=0 "
                        "--set shadow.enabled=0",
                        "0.1 print\n0.2 press down\n0.2 press down\n0.2 press down\n0.2 press down\n0.5 press enter\n0.8 press up\n"
                        "1.5 press right\n2.5 print\n2.6 quit\n");
    ASSERT_EQ(r.size(), 2u);
    EXPECT_EQ(r[0].mode, "walk");
    EXPECT_EQ(r[1].position, glm::vec3(0.0f, 2.0f, 0.0f));
    EXPECT_EQ(r[1].mode, "fly");
}

// The panel at the three window sizes: the screenshot has the window's size and the panel is drawn in its
// place (its layout is checked in tests/panel_fit_test.cpp).
void expectPanelDrawn(int w, int h) {
    fs::path dir = test::testOutputDir() / "window-walk";
    fs::create_directories(dir);
    std::string size = std::to_string(w) + "x" + std::to_string(h);
    fs::path shot = dir / ("panel_" + size + ".png");
    std::string command = std::string(GLIMMER_EXECUTABLE) + " view --scene plane90 --env none --method smooth --size " +
                          size + " --frames 2 --screenshot " + shot.string() + " > /dev/null 2>&1";
    ASSERT_EQ(test::runUnderXvfb(command, "1920x1080x24"), 0) << size;
    ImageF image = readImage(shot);
    ASSERT_EQ(image.width, w);
    ASSERT_EQ(image.height, h);
    // The panel background colour (ui::palette::kPanel, 18 20 26) down the panel's left padding.
    int scale = h >= 600 ? 2 : 1, panelPixels = 0;
    for (int y = 8 * scale; y < 8 * scale + 100; ++y) {
        float r = image.at(4 * scale + 1, y, 0) * 255.0f, g = image.at(4 * scale + 1, y, 1) * 255.0f;
        panelPixels += std::abs(r - 18.0f) < 1.5f && std::abs(g - 20.0f) < 1.5f;
    }
    EXPECT_GT(panelPixels, 80) << size;
}

TEST(WindowWalk, PanelIsDrawnAt960x540) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    expectPanelDrawn(960, 540);
}
TEST(WindowWalk, PanelIsDrawnAt1280x720) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    expectPanelDrawn(1280, 720);
}
TEST(WindowWalk, PanelIsDrawnAt1920x1080) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run not installed";
    expectPanelDrawn(1920, 1080);
}

}  // namespace
}  // namespace glimmer
