// The AOV ids have one source, shaders/common/aov_ids.glsl, included by the shaders (through common/frame.glsl) and by
// the table of names in engine/render/aov.cpp. These checks catch the ways the two sides can still drift apart: a
// table entry whose id no shader knows, a shader view no name reaches, a name bound to another view's id, or a
// VIEW_ constant declared somewhere else in the shaders. Reads the sources as text; no GL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "render/aov.h"

namespace {

namespace fs = std::filesystem;

const fs::path kShaders = fs::path(GLIMMER_SOURCE_DIR) / "shaders";

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// VIEW_NAME -> id, from the #define lines of the shared header.
std::map<std::string, int> headerIds() {
    std::map<std::string, int> ids;
    std::istringstream lines(readText(kShaders / "common" / "aov_ids.glsl"));
    const std::regex define(R"(^\s*#\s*define\s+VIEW_([A-Z0-9_]+)\s+(\d+)\b.*)");
    std::string line;
    std::smatch m;
    while (std::getline(lines, line))
        if (std::regex_match(line, m, define)) ids[m[1].str()] = std::stoi(m[2].str());
    return ids;
}

// The view a table name stands for: its own name in capitals, except these two.
std::string viewNameOf(const std::string& aovName) {
    static const std::map<std::string, std::string> aliases = {
        {"material", "ROUGHNESS_METALLIC"},   // R alpha, G metallic, B material id
        {"glintscale", "EXTRA"},              // wang2020's name for its extra channel
    };
    if (auto it = aliases.find(aovName); it != aliases.end()) return it->second;
    std::string upper = aovName;
    std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return char(std::toupper(c)); });
    return upper;
}

TEST(AovIds, EveryTableNameHasItsViewsIdFromTheSharedHeader) {
    const std::map<std::string, int> ids = headerIds();
    ASSERT_GE(ids.size(), 15u) << "no VIEW_ defines read from shaders/common/aov_ids.glsl";
    std::set<int> named;
    for (const glimmer::AovInfo& aov : glimmer::aovTable()) {
        auto it = ids.find(viewNameOf(aov.name));
        ASSERT_NE(it, ids.end()) << "--aov " << aov.name << ": no VIEW_" << viewNameOf(aov.name)
                                 << " in shaders/common/aov_ids.glsl";
        EXPECT_EQ(aov.viewId, it->second) << "--aov " << aov.name << " selects view " << aov.viewId
                                          << " but the shaders' VIEW_" << it->first << " is " << it->second;
        named.insert(aov.viewId);
    }
    std::set<int> distinct;
    for (const auto& [name, id] : ids) {
        EXPECT_TRUE(distinct.insert(id).second) << "VIEW_" << name << ": id " << id << " used twice";
        EXPECT_TRUE(named.count(id)) << "VIEW_" << name << " (" << id << ") has no --aov name in engine/render/aov.cpp";
    }
}

TEST(AovIds, NoShaderDeclaresAViewIdOfItsOwn) {
    const std::regex ownView(R"((#\s*define\s+VIEW_[A-Z0-9_]+\s)|(\bint\s+VIEW_[A-Z0-9_]+\s*=))");
    int files = 0;
    for (const auto& entry : fs::recursive_directory_iterator(kShaders)) {
        if (!entry.is_regular_file() || entry.path().filename() == "aov_ids.glsl") continue;
        const std::string ext = entry.path().extension().string();
        if (ext == ".md") continue;
        ++files;
        EXPECT_FALSE(std::regex_search(readText(entry.path()), ownView))
            << fs::relative(entry.path(), kShaders).string() << " declares a VIEW_ id outside common/aov_ids.glsl";
    }
    EXPECT_GT(files, 50);
    EXPECT_NE(readText(kShaders / "common" / "frame.glsl").find("#include \"common/aov_ids.glsl\""), std::string::npos)
        << "common/frame.glsl no longer gives the shaders the shared ids";
}

}  // namespace
