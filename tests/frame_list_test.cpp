// The frame list (render/renderer.cpp buildFrameList) and the frame resources its passes declare
// (render/frame/frame_resources.h): the list is consistent for every kind of frame and method, the check finds a
// pass that reads what no earlier pass wrote, and a pass that touches a resource it did not declare fails loudly.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/files.h"
#include "glints/methods.h"
#include "platform/context.h"
#include "render/frame/frame_resources.h"
#include "render/renderer.h"

namespace glimmer {
namespace {

std::vector<std::string> names(const std::vector<DeclaredPass>& list) {
    std::vector<std::string> out;
    for (const DeclaredPass& p : list) out.push_back(p.name);
    return out;
}

TEST(FrameList, EveryReadHasAnEarlierWriterForEveryMethodAndKind) {
    auto context = createHeadlessContext(Backend::Egl);
    for (const GlintMethod& method : glintMethods()) {
        RenderSettings settings;
        settings.method = method.id;
        for (FrameKind kind : {FrameKind::Full, FrameKind::Capture}) {
            Renderer renderer(defaultShaderDir(), settings, kind);
            std::vector<DeclaredPass> list = renderer.frameList();
            for (const std::string& problem : checkFrameList(list)) ADD_FAILURE() << method.id << ": " << problem;
            std::vector<std::string> order = names(list);
            ASSERT_GE(order.size(), 8u);
            EXPECT_EQ(order.front(), "shadow_sun");
            if (kind == FrameKind::Capture) {
                EXPECT_EQ(order.back(), "lighting") << "a capture ends with the lighting pass";
                continue;
            }
            EXPECT_EQ(order.back(), "tonemap");
            // The method's own passes sit right after lighting (wang2020: its Sec. 4.4 blurs), before forward_save.
            auto at = [&](const std::string& name) { return std::find(order.begin(), order.end(), name) - order.begin(); };
            const long methodPasses = at("forward_save") - at("lighting") - 1;
            EXPECT_EQ(methodPasses, method.createPasses ? 2 : 0) << method.id;
        }
    }
}

TEST(FrameResources, TheCheckFindsAReadBeforeItsWriterAndAHistoryNobodyWrites) {
    std::vector<DeclaredPass> list = {
        {"lighting", {.reads = {FrameResource::GBuffer}, .writes = {FrameResource::Hdr}}},
        {"gbuffer", {.writes = {FrameResource::GBuffer}}},
        {"restore", {.writes = {FrameResource::Hdr}, .readsPrevious = {FrameResource::OpaqueMean}}},
    };
    std::vector<std::string> problems = checkFrameList(list);
    ASSERT_EQ(problems.size(), 2u);
    EXPECT_NE(problems[0].find("lighting reads gbuffer"), std::string::npos) << problems[0];
    EXPECT_NE(problems[1].find("opaque_mean"), std::string::npos) << problems[1];
    std::swap(list[0], list[1]);
    list.push_back({"save", {.reads = {FrameResource::Hdr}, .writes = {FrameResource::OpaqueMean}}});
    EXPECT_TRUE(checkFrameList(list).empty()) << "a history written later in the list is read from the last frame";
}

TEST(FrameResources, AnUndeclaredAccessThrowsAndADeclaredOneDoesNot) {
    FrameResources resources;
    resources.publish(FrameResource::Depth, {.textures = {7}, .width = 4, .height = 4});
    const PassResources declared{.reads = {FrameResource::Depth}, .writes = {FrameResource::Hdr}};
    resources.beginPass("test", &declared);
    EXPECT_EQ(resources.read(FrameResource::Depth).texture(), 7u);
    EXPECT_NO_THROW(resources.write(FrameResource::Hdr));
    EXPECT_THROW(resources.read(FrameResource::GBuffer), Error);
    EXPECT_THROW(resources.write(FrameResource::Depth), Error) << "declared as read, not written";
    resources.endPass();
    EXPECT_NO_THROW(resources.read(FrameResource::GBuffer)) << "outside a pass the renderer reads anything";
}

TEST(FrameResources, RepublishingTheSameObjectsKeepsTheSerial) {
    FrameResources resources;
    resources.publish(FrameResource::Hdr, {.textures = {3}, .width = 8, .height = 8});
    const uint64_t first = resources.get(FrameResource::Hdr).serial;
    resources.publish(FrameResource::Hdr, {.textures = {3}, .width = 8, .height = 8});
    EXPECT_EQ(resources.get(FrameResource::Hdr).serial, first);
    resources.publish(FrameResource::Hdr, {.textures = {4}, .width = 8, .height = 8});
    EXPECT_NE(resources.get(FrameResource::Hdr).serial, first) << "framebuffers over the old texture must be rebuilt";
}

}  // namespace
}  // namespace glimmer
