// The README stays a newcomer's page (under 20 KB; the long form lives in docs/), and the documentation's links
// lead somewhere: every relative link of README.md and docs/*.md names a file that exists, and docs/index.md lists
// every page of docs/. Reads the Markdown as text; links inside code blocks are not links.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kRoot = GLIMMER_SOURCE_DIR;

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The Markdown without its fenced code blocks.
std::string withoutCodeBlocks(const std::string& markdown) {
    std::istringstream lines(markdown);
    std::string line, out;
    bool inside = false;
    while (std::getline(lines, line)) {
        if (line.rfind("```", 0) == 0) {
            inside = !inside;
            continue;
        }
        if (!inside) out += line + "\n";
    }
    return out;
}

// Targets of the inline links and images, [text](target), that point into the repository.
std::vector<std::string> relativeLinks(const std::string& markdown) {
    std::vector<std::string> links;
    const std::regex link(R"(\]\(([^)\s]+)\))");
    const std::string text = withoutCodeBlocks(markdown);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), link); it != std::sregex_iterator(); ++it) {
        std::string target = (*it)[1].str();
        if (target.empty() || target[0] == '#' || target.find("://") != std::string::npos ||
            target.rfind("mailto:", 0) == 0)
            continue;
        links.push_back(target.substr(0, target.find('#')));
    }
    return links;
}

std::vector<fs::path> markdownPages() {
    std::vector<fs::path> pages = {kRoot / "README.md"};
    for (const auto& entry : fs::directory_iterator(kRoot / "docs"))
        if (entry.path().extension() == ".md") pages.push_back(entry.path());
    return pages;
}

TEST(Docs, ReadmeStaysUnder20KB) {
    const auto bytes = fs::file_size(kRoot / "README.md");
    EXPECT_LT(bytes, 20u * 1024u) << "README.md is " << bytes << " bytes: move the details to a page of docs/";
}

TEST(Docs, EveryRelativeLinkNamesAFileThatExists) {
    int checked = 0;
    for (const fs::path& page : markdownPages()) {
        for (const std::string& target : relativeLinks(readText(page))) {
            ++checked;
            const fs::path resolved = page.parent_path() / target;
            EXPECT_TRUE(fs::exists(resolved)) << fs::relative(page, kRoot).string() << ": link to " << target
                                              << " (no file " << fs::relative(resolved.lexically_normal(), kRoot).string()
                                              << ")";
        }
    }
    EXPECT_GT(checked, 200) << "the link pattern no longer finds the documentation's links";
}

TEST(Docs, TheIndexListsEveryPage) {
    std::set<std::string> listed;
    for (const std::string& target : relativeLinks(readText(kRoot / "docs" / "index.md"))) listed.insert(target);
    for (const fs::path& page : markdownPages()) {
        if (page.parent_path().filename() != "docs" || page.filename() == "index.md") continue;
        EXPECT_TRUE(listed.count(page.filename().string())) << "docs/index.md does not list " << page.filename();
    }
}

}  // namespace
