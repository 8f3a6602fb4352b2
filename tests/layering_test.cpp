// The include layering of engine/ (docs/renderer.md, "Folders and layers"): each top-level folder may include only
// the folders below it, so a method never reaches into the renderer, the renderer never into the offscreen session
// or the window, and the CPU references stay out of everything the renderer links. Reads the sources as text.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

namespace {

namespace fs = std::filesystem;

// What each folder of engine/ may include besides itself. Kept in the order of docs/renderer.md's diagram.
const std::map<std::string, std::set<std::string>>& allowedIncludes() {
    static const std::map<std::string, std::set<std::string>> allowed = [] {
        std::map<std::string, std::set<std::string>> a;
        a["core"] = {};
        a["gl"] = {"core"};
        a["platform"] = {"core"};
        a["scene"] = {"core"};
        a["glints"] = {"core", "gl", "scene"};
        a["environment"] = {"core", "gl", "scene", "glints"};
        a["render"] = {"core", "gl", "platform", "scene", "glints", "environment"};
        a["offscreen"] = {"core", "gl", "platform", "scene", "glints", "environment", "render"};
        a["ui"] = {"core", "gl", "platform", "scene", "glints", "environment", "render"};
        a["reference"] = {"core", "gl", "platform", "scene", "glints", "environment", "render", "offscreen"};
        a["checks"] = {"core", "gl", "platform", "scene", "glints", "environment", "render", "offscreen", "reference"};
        a["bench"] = {"core", "gl", "platform", "scene", "glints", "environment", "render", "offscreen", "ui"};
        a["app"] = {"core", "gl",        "platform", "scene",  "glints", "environment", "render",
                    "offscreen", "ui", "reference", "checks", "bench"};
        return a;
    }();
    return allowed;
}

struct Violation {
    std::string file, include;
};

std::vector<Violation> layeringViolations(const fs::path& engine, std::set<std::string>& unknownFolders) {
    const auto& allowed = allowedIncludes();
    const std::regex includeLine(R"(^\s*#\s*include\s*"([^"]+)\")");
    std::vector<Violation> violations;
    for (const auto& entry : fs::recursive_directory_iterator(engine)) {
        if (!entry.is_regular_file()) continue;
        const std::string ext = entry.path().extension().string();
        if (ext != ".h" && ext != ".cpp" && ext != ".inl") continue;
        const std::string relative = fs::relative(entry.path(), engine).generic_string();
        const std::string folder = relative.substr(0, relative.find('/'));
        auto rules = allowed.find(folder);
        if (rules == allowed.end()) {
            unknownFolders.insert(folder);
            continue;
        }
        std::ifstream in(entry.path());
        std::string line;
        std::smatch m;
        while (std::getline(in, line)) {
            if (line.size() > 300 || !std::regex_search(line, m, includeLine)) continue;
            const std::string target = m[1].str();
            if (!fs::exists(engine / target)) continue;   // shaders/ (bindings.glsl), system or relative headers
            const std::string targetFolder = target.substr(0, target.find('/'));
            if (targetFolder != folder && !rules->second.count(targetFolder))
                violations.push_back({relative, target});
        }
    }
    return violations;
}

TEST(IncludeLayering, EveryEngineFolderIncludesOnlyTheFoldersBelowIt) {
    const fs::path engine = fs::path(GLIMMER_SOURCE_DIR) / "engine";
    std::set<std::string> unknown;
    std::vector<Violation> violations = layeringViolations(engine, unknown);
    for (const Violation& v : violations) ADD_FAILURE() << v.file << " includes " << v.include;
    for (const std::string& folder : unknown)
        ADD_FAILURE() << "engine/" << folder << "/ has no place in the layering (tests/layering_test.cpp, docs/renderer.md)";
}

// The rule must be able to fail: a renderer file that includes the offscreen session is caught.
TEST(IncludeLayering, AnUpwardIncludeIsCaught) {
    const fs::path root = fs::path(GLIMMER_TEST_OUTPUT_DIR) / "layering";
    fs::remove_all(root);
    fs::create_directories(root / "render");
    fs::create_directories(root / "offscreen");
    std::ofstream(root / "offscreen" / "offscreen.h") << "#pragma once\n";
    std::ofstream(root / "render" / "renderer.cpp") << "#include \"offscreen/offscreen.h\"\n";
    std::set<std::string> unknown;
    std::vector<Violation> violations = layeringViolations(root, unknown);
    ASSERT_EQ(violations.size(), 1u);
    EXPECT_EQ(violations[0].file, "render/renderer.cpp");
    EXPECT_TRUE(unknown.empty());
}

}  // namespace
