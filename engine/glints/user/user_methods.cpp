#include "glints/user/user_methods.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/files.h"
#include "glints/glint_mapping.h"
#include "glints/user/method_header.h"

namespace glimmer {
namespace fs = std::filesystem;

namespace {

constexpr const char* kHeaderOpen = "/* glimmer-method";
static_assert(kMaxUserMethodParams == kMaxMethodParams, "one parameter capacity for user methods and the GPU block");

}  // namespace

GlintMethod parseUserMethodHeader(const std::string& text, const std::string& fileLabel) {
    const GlintMethod* from = nullptr;
    // "resources:" names a built-in whose GPU resources the method borrows.
    MethodHeader header = parseMethodHeader(text, fileLabel, [&](const std::string& builtIn) -> std::string {
        for (const GlintMethod& m : glintMethods())
            if (m.id == builtIn && !m.isUserMethod()) from = &m;
        if (!from) return "resources: '" + builtIn.substr(0, 64) + "' is not a built-in method";
        if (!from->createResources) return "resources: built-in method '" + builtIn + "' has no GPU resources";
        return "";
    });
    GlintMethod method;
    method.id = header.id;
    method.title = header.title;
    method.citation = header.citation;
    method.params = header.params;
    method.materialMapping = header.materialMapping;
    method.convergence = header.convergence;
    method.resourcesFrom = header.resourcesFrom;
    if (from) {
        method.createResources = from->createResources;
        // A method built on a built-in's code (and resources) draws its environment glints when that code does
        // (deliot2023's glintEnvironmentFactor): the renderer then builds the environment's levels for it too.
        method.environmentGlints = from->environmentGlints;
        // The borrowed resources are built from the shared values of the material the built-in chooses.
        for (const ParamSpec& p : method.params)
            if (p.name == from->sharedDataMaterial) method.sharedDataMaterial = from->sharedDataMaterial;
    }
    return method;
}

GlintMethod readUserMethodFile(const fs::path& path) {
    // readInputFile refuses anything but a regular file of at most 4 MiB, naming the path.
    std::string text = readInputFile(path, kMethodFileInput);
    std::error_code ec;
    fs::path canonical = fs::canonical(path, ec);
    if (ec) throw Error(path.string() + ": cannot resolve the path");
    GlintMethod method = parseUserMethodHeader(text, displayPath(canonical));
    method.sourceFile = canonical;
    method.shaderFile = canonical.string();   // absolute: the include resolves it as is (gl/program.h)
    std::string upper = method.id;
    std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
    method.define = "GLINT_METHOD_USER_" + upper;
    return method;
}

std::string loadUserMethodFile(const fs::path& path) {
    GlintMethod method = readUserMethodFile(path);
    std::string id = method.id;
    registerGlintMethod(std::move(method));
    return id;
}

std::string resolveGlintMethod(const std::string& spec, const std::string& flag) {
    if (spec.rfind("file:", 0) == 0) {
        std::string path = spec.substr(5);
        if (path.empty()) throw UsageError(flag + ": 'file:' needs a path (file:my_glints.glsl)");
        std::error_code ec;
        if (const GlintMethod* loaded = userMethodForFile(fs::canonical(path, ec)); loaded && !ec) return loaded->id;
        return loadUserMethodFile(path);
    }
    for (const GlintMethod& m : glintMethods())
        if (m.id == spec) return m.id;
    std::string known;
    for (const GlintMethod& m : glintMethods()) known += (known.empty() ? "" : ", ") + m.id;
    throw UsageError(flag + ": unknown method '" + spec + "' (known: " + known + "; a user method: file:PATH.glsl)");
}

const GlintMethod* userMethodForFile(const fs::path& file) {
    for (const GlintMethod& m : glintMethods())
        if (m.isUserMethod() && m.sourceFile == file) return &m;
    return nullptr;
}

std::vector<fs::path> methodFilesIn(const fs::path& folder) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (auto it = fs::directory_iterator(folder, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
        if (it->path().extension() != ".glsl" || !it->is_regular_file()) continue;
        try {
            std::string text = readInputFile(it->path(), kMethodFileInput);
            if (text.find(kHeaderOpen) != std::string::npos) files.push_back(fs::canonical(it->path()));
        } catch (const std::exception&) {
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

ParamValues carryParamValues(const ParamValues& values, const GlintMethod& method) {
    ParamValues kept;
    for (const ParamSpec& spec : method.params) {
        auto it = values.find(spec.name);
        if (it == values.end()) continue;
        float v = std::clamp(it->second, spec.minValue, spec.maxValue);
        if (spec.integer || !spec.choices.empty()) v = std::round(v);
        kept[spec.name] = v;
    }
    return kept;
}

}  // namespace glimmer
