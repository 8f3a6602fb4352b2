// Walking and flying without a window: key holds over irregular frames, time-based motion with a stall cap,
// Bullet collision on a small hand-built scene (floor, wall, a climbable step and a ledge too high to climb),
// the input-script parser and recorded camera paths.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "scene/character_collision.h"
#include "support/process.h"
#include "ui/input_script.h"
#include "ui/key_holds.h"
#include "ui/player_motion.h"
#include "ui/recorded_path.h"

namespace glimmer {
namespace {

// An axis-aligned box as 12 triangles (outward winding does not matter to the collision).
void addBox(MeshData& mesh, glm::vec3 lo, glm::vec3 hi) {
    uint32_t base = uint32_t(mesh.positions.size());
    for (int i = 0; i < 8; ++i)
        mesh.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
    const uint32_t faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto& f : faces)
        for (uint32_t k : {f[0], f[1], f[2], f[0], f[2], f[3]}) mesh.indices.push_back(base + k);
}

// Floor y = 0 over [-20, 20]^2; a wall (box) with its face at x = 5; a 0.3 m step at x in [-6, -3] and a
// 0.6 m ledge at z in [6, 9] (x in [-2, 2]).
Scene testScene() {
    Scene scene;
    scene.name = "walk-test";
    MeshData mesh;
    addBox(mesh, {-20, -1, -20}, {20, 0, 20});
    addBox(mesh, {5, 0, -20}, {6, 4, 20});
    addBox(mesh, {-6, 0, -2}, {-3, 0.3f, 2});
    addBox(mesh, {-2, 0, 6}, {2, 0.6f, 9});
    scene.meshes.push_back(mesh);
    scene.instances.push_back({0, 0, glm::mat4(1.0f)});
    return scene;
}

// Walks with a constant velocity for `seconds` in 1/30 s steps.
void walk(SceneCollision& body, glm::vec3 velocity, float seconds) {
    for (int i = 0; i < int(std::lround(seconds * 30.0f)); ++i) body.step(velocity, 1.0f / 30.0f);
}

TEST(WalkKeys, HeldSecondsCountOverlapsAndTapsBetweenFrames) {
    ui::KeyHolds keys;
    keys.press(1, 0.25);
    keys.release(1, 1.75);
    EXPECT_NEAR(keys.heldSeconds(1, 0.0, 1.0), 0.75, 1e-12);
    EXPECT_NEAR(keys.heldSeconds(1, 1.0, 3.0), 0.75, 1e-12);
    EXPECT_EQ(keys.heldSeconds(2, 0.0, 3.0), 0.0);
    // Press and release delivered at one poll: still a tap of kMinimumTapSeconds.
    keys.press(3, 2.0);
    keys.release(3, 2.0);
    EXPECT_NEAR(keys.heldSeconds(3, 1.9, 5.0), ui::kMinimumTapSeconds, 1e-12);
    keys.press(4, 1.0);
    EXPECT_TRUE(keys.down(4));
    EXPECT_NEAR(keys.heldSeconds(4, 0.0, 2.5), 1.5, 1e-12);
    keys.forgetBefore(10.0);
    EXPECT_EQ(keys.heldSeconds(1, 0.0, 3.0), 0.0);
    EXPECT_TRUE(keys.down(4));  // still held
}

// Flying: a key held 2 s moves speed x 2 s whatever the frame intervals; a stall moves one step at most.
TEST(WalkMotion, FlyingMovesSpeedTimesHeldTimeOverIrregularFrames) {
    ui::PlayerMotion motion(nullptr);
    Camera start;
    start.position = {0, 1, 0};
    start.target = {0, 1, -1};
    motion.setCamera(start, ui::MoveMode::Walk);
    EXPECT_EQ(motion.mode(), ui::MoveMode::Fly);  // no collision: flying only
    auto holdW = [](double from, double to) { return [=](ui::MoveKey key, double a, double b) {
        return key == ui::MoveKey::Forward ? std::max(0.0, std::min(b, to) - std::max(a, from)) : 0.0;
    }; };
    const double frames[] = {0.0, 0.016, 0.31, 0.33, 0.9, 1.35, 1.36, 2.05, 2.6, 3.0};
    for (size_t i = 1; i < std::size(frames); ++i) motion.advance(holdW(0.4, 2.4), frames[i - 1], frames[i], 1.5f);
    EXPECT_NEAR(glm::length(motion.camera().position - start.position), 1.5 * 2.0, 1e-4);
    EXPECT_NEAR(motion.camera().position.z, -3.0f, 1e-4f);
    EXPECT_EQ(motion.camera().forward(), start.forward());

    motion.setCamera(start, ui::MoveMode::Fly);
    motion.advance(holdW(0.0, 100.0), 0.0, 5.0, 1.0f);  // one 5 s frame: a stall, not a 5 m jump
    EXPECT_NEAR(glm::length(motion.camera().position - start.position), ui::kMaxStepSeconds, 1e-5);
    motion.setCamera(start, ui::MoveMode::Fly);
    motion.advance(holdW(0.0, 100.0), 0.0, 0.35, 2.0f);  // 0.35 s in four steps: all of it counts
    EXPECT_NEAR(glm::length(motion.camera().position - start.position), 0.7, 1e-5);
}

TEST(WalkCollision, AFallLandsOnTheFloorAtStandingHeight) {
    SceneCollision body(testScene());
    EXPECT_TRUE(body.standingAt({0, 1.7f, 0}, 0.05f));
    EXPECT_FALSE(body.standingAt({0, 5.0f, 0}, 0.2f));
    body.placeEye({0, 6.0f, 0});
    walk(body, {0, 0, 0}, 3.0f);
    EXPECT_NEAR(body.eye().y, 1.7f, 0.03f);
    EXPECT_NEAR(body.eye().x, 0.0f, 1e-3f);
    EXPECT_TRUE(body.onGround());
}

TEST(WalkCollision, WalkingIntoAWallStopsAtItAndSlidesAlongIt) {
    SceneCollision body(testScene());
    body.placeEye({0, 1.7f, 0});
    walk(body, {3.0f, 0, 0}, 4.0f);  // 12 m towards a wall 5 m away
    float stop = 5.0f - body.body().radius;
    EXPECT_LE(body.eye().x, stop + 0.01f);
    EXPECT_GE(body.eye().x, stop - 0.1f);
    EXPECT_NEAR(body.eye().y, 1.7f, 0.05f);
    // Diagonally into the wall: the along-wall part of the motion carries on.
    float z0 = body.eye().z;
    walk(body, {2.0f, 0, 2.0f}, 2.0f);
    EXPECT_LE(body.eye().x, stop + 0.01f);
    EXPECT_GT(body.eye().z - z0, 2.0f);  // 4 m asked along z; sliding keeps most of it
}

TEST(WalkCollision, StepsUpASmallLedgeButNotATallOne) {
    SceneCollision body(testScene());
    body.placeEye({0, 1.7f, 0});
    walk(body, {-2.0f, 0, 0}, 2.5f);  // onto the 0.3 m step (x < -3)
    EXPECT_LT(body.eye().x, -3.2f);
    EXPECT_NEAR(body.eye().y, 2.0f, 0.05f);
    body.placeEye({0, 1.7f, 0});
    walk(body, {0, 0, 2.0f}, 4.0f);  // into the 0.6 m ledge starting at z = 6
    EXPECT_LT(body.eye().z, 6.0f - 0.2f);  // the capsule's round bottom touches the ledge's edge a little closer
    EXPECT_NEAR(body.eye().y, 1.7f, 0.05f);
}

TEST(WalkCollision, WalkingModeNeedsACameraStandingOnAFloor) {
    SceneCollision body(testScene());
    ui::PlayerMotion motion(&body);
    Camera standing;
    standing.position = {0, 1.7f, 0};
    standing.target = {1, 1.7f, 0};
    EXPECT_EQ(motion.setCamera(standing, ui::MoveMode::Walk), ui::MoveMode::Walk);
    EXPECT_EQ(motion.camera().position, standing.position);  // an unmoved camera stays exact
    Camera high = standing;
    high.position.y = 8.0f;
    high.target.y = 8.0f;
    EXPECT_EQ(motion.setCamera(high, ui::MoveMode::Walk), ui::MoveMode::Fly);
    // Switching to walking there falls to the floor; flying moves through the wall.
    EXPECT_TRUE(motion.setMode(ui::MoveMode::Walk));
    auto none = [](ui::MoveKey, double, double) { return 0.0; };
    for (int i = 0; i < 40; ++i) motion.advance(none, i * 0.05, (i + 1) * 0.05, 1.0f);
    EXPECT_NEAR(motion.camera().position.y, 1.7f, 0.03f);
    motion.setMode(ui::MoveMode::Fly);
    // Outside the floor's extent there is nothing to land on: walking is refused instead of falling forever.
    Camera outside = high;
    outside.position.x = 50.0f;
    outside.target.x = 51.0f;
    motion.setCamera(outside, ui::MoveMode::Fly);
    EXPECT_FALSE(motion.setMode(ui::MoveMode::Walk));
    EXPECT_EQ(motion.mode(), ui::MoveMode::Fly);
    motion.setCamera(high, ui::MoveMode::Fly);
    auto forward = [](ui::MoveKey key, double a, double b) { return key == ui::MoveKey::Forward ? b - a : 0.0; };
    motion.advance(forward, 0.0, 0.5, 20.0f);
    EXPECT_GT(motion.camera().position.x, 6.0f);
}

TEST(WalkInputScript, ParsesEventsInTimeOrderAndNamesBadLines) {
    auto events = ui::parseInputScript("# comment\n1.5 up w\n0.5 down w  # hold\n2 press f5\n2 look 10 -4\n3 print\n"
                                       "3 screenshot a.png\n4 quit\n", "s.txt");
    ASSERT_EQ(events.size(), 7u);
    EXPECT_EQ(events[0].kind, ui::ScriptEvent::Kind::Down);
    EXPECT_EQ(events[0].key, ui::keyFromName("W"));
    EXPECT_EQ(events[1].kind, ui::ScriptEvent::Kind::Up);
    EXPECT_EQ(events[2].key, ui::keyFromName("f5"));
    EXPECT_EQ(events[3].dy, -4.0f);
    EXPECT_EQ(events[5].path, "a.png");
    ui::ScriptPlayer player(events);
    auto countDue = [&](double seconds) {
        size_t n = 0;
        while (player.nextDue(seconds)) ++n;
        return n;
    };
    EXPECT_EQ(countDue(1.0), 1u);
    EXPECT_EQ(countDue(2.0), 3u);
    EXPECT_FALSE(player.finished());
    for (const char* bad : {"x down w", "1 down", "1 down nokey", "1 jump", "1 look 3", "-1 quit", "1 quit now"}) {
        try {
            ui::parseInputScript(std::string("\n") + bad + "\n", "s.txt");
            ADD_FAILURE() << bad;
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()).rfind("s.txt:2: ", 0), 0u) << e.what();
        }
    }
}

TEST(WalkRecordedPath, SavesLoadsAndInterpolatesDeterministically) {
    ui::RecordedPath path;
    Camera a, b;
    a.position = {0, 1.7f, 0};
    a.target = {0, 1.7f, -1};
    b.position = {2, 1.7f, 0};
    b.target = {3, 1.7f, 0};
    b.verticalFovDegrees = 60.0f;
    path.add(10.0, a);
    path.add(10.01, b);  // closer than 1/30 s: dropped
    path.add(12.0, b);
    EXPECT_EQ(path.samples().size(), 2u);
    EXPECT_DOUBLE_EQ(path.duration(), 2.0);
    Camera mid = path.at(1.0);
    EXPECT_NEAR(mid.position.x, 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(mid.forward(), glm::normalize(glm::vec3(1, 0, -1))), 1.0f, 1e-5f);  // halfway on the sphere
    EXPECT_NEAR(mid.verticalFovDegrees, 52.5f, 1e-4f);
    EXPECT_EQ(path.at(-1.0).position, a.position);
    EXPECT_EQ(path.at(99.0).position, b.position);

    std::filesystem::path file = std::filesystem::path(test::makeTempDir("walk-path")) / "p.path.json";
    path.save(file, "walk-test");
    ui::RecordedPath loaded = ui::RecordedPath::load(file);
    EXPECT_EQ(loaded.sceneName, "walk-test");
    ASSERT_EQ(loaded.samples().size(), 2u);
    for (double t : {0.0, 0.3, 1.0, 1.7, 2.0}) {
        EXPECT_NEAR(glm::length(loaded.at(t).position - path.at(t).position), 0.0f, 1e-5f) << t;
        EXPECT_NEAR(glm::length(loaded.at(t).target - path.at(t).target), 0.0f, 1e-5f) << t;
    }
    std::ofstream(file.string() + ".bad") << "{\"samples\": [{\"t\": 0, \"position\": [0, 1]}]}";
    EXPECT_THROW(ui::RecordedPath::load(file.string() + ".bad"), Error);
}

}  // namespace
}  // namespace glimmer
