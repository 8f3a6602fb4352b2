#include "glints/user/user_methods.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <regex>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/files.h"
#include "glints/glint_mapping.h"

namespace glimmer {
namespace fs = std::filesystem;

namespace {

constexpr const char* kHeaderOpen = "/* glimmer-method";
// A user method file larger than this is not a shader (the header parser reads the whole file).
constexpr size_t kMaxMethodFileBytes = 4u << 20;

std::string trim(const std::string& s) {
    size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    size_t b = s.find_last_not_of(" \t\r");
    return s.substr(a, b - a + 1);
}

bool validName(const std::string& name) {
    static const std::regex pattern("[a-z][a-z0-9_]*");
    return name.size() <= 48 && std::regex_match(name, pattern);
}

// Strictly parsed finite number (no trailing text).
bool parseNumber(const std::string& text, float& value) {
    std::string t = trim(text);
    if (t.empty()) return false;
    char* end = nullptr;
    value = std::strtof(t.c_str(), &end);
    return end == t.c_str() + t.size() && std::isfinite(value);
}

class HeaderParser {
public:
    HeaderParser(const std::string& label) : label_(label) {}

    [[noreturn]] void fail(int line, const std::string& message) const {
        throw Error(label_ + ":" + std::to_string(line) + ": " + message);
    }

    GlintMethod parse(const std::string& text) {
        std::istringstream lines(text);
        std::string line;
        int number = 0, openLine = 0;
        bool inside = false, closed = false;
        int convergeLine = 0;
        std::string convergeText;
        std::vector<std::pair<int, std::string>> mapLines;
        while (std::getline(lines, line)) {
            ++number;
            if (!inside) {
                if (trim(line).rfind(kHeaderOpen, 0) == 0) {
                    std::string rest = trim(trim(line).substr(std::string(kHeaderOpen).size()));
                    if (!rest.empty()) fail(number, "text after '" + std::string(kHeaderOpen) + "' (keys go on the lines below)");
                    inside = true;
                    openLine = number;
                }
                continue;
            }
            std::string body = line;
            size_t close = body.find("*/");
            if (close != std::string::npos) {
                if (!trim(body.substr(close + 2)).empty()) fail(number, "code after the header's closing */");
                body = body.substr(0, close);
                closed = true;
            }
            body = trim(body);
            if (!body.empty() && body[0] == '*') body = trim(body.substr(1));   // " * key: value" style
            if (!body.empty() && body[0] != '#') {
                size_t colon = body.find(':');
                if (colon == std::string::npos) fail(number, "expected 'key: value' (keys: name, title, citation, param, map, converge, resources)");
                std::string key = trim(body.substr(0, colon)), value = trim(body.substr(colon + 1));
                if (key == "name") setOnce(number, "name", method_.id, value);
                else if (key == "title") setOnce(number, "title", method_.title, value);
                else if (key == "citation") setOnce(number, "citation", method_.citation, value);
                else if (key == "resources") setOnce(number, "resources", method_.resourcesFrom, value);
                else if (key == "param") parseParam(number, value);
                else if (key == "map") mapLines.push_back({number, value});
                else if (key == "converge") {
                    if (convergeLine) fail(number, "'converge' given twice (first on line " + std::to_string(convergeLine) + ")");
                    convergeLine = number;
                    convergeText = value;
                } else {
                    fail(number, "unknown key '" + key + "' (keys: name, title, citation, param, map, converge, resources)");
                }
            }
            if (closed) break;
        }
        if (!inside) fail(1, "no header block: the file must contain a comment opening with '" + std::string(kHeaderOpen) + "'");
        if (!closed) fail(openLine, "the header block opened here is not closed with */");
        if (method_.id.empty()) fail(openLine, "the header has no 'name'");
        if (!validName(method_.id)) fail(keyLines_["name"], "name '" + method_.id + "' must be lower-case letters, digits and _, starting with a letter (at most 48)");
        if (method_.citation.empty()) fail(openLine, "the header has no 'citation' (say where the idea comes from)");
        if (method_.title.empty()) method_.title = method_.id;
        if (!method_.resourcesFrom.empty()) {
            const GlintMethod* from = nullptr;
            for (const GlintMethod& m : glintMethods())
                if (m.id == method_.resourcesFrom && !m.isUserMethod()) from = &m;
            if (!from) fail(keyLines_["resources"], "resources: '" + method_.resourcesFrom + "' is not a built-in method");
            if (!from->createResources) fail(keyLines_["resources"], "resources: built-in method '" + method_.resourcesFrom + "' has no GPU resources");
            method_.createResources = from->createResources;
            // A method built on a built-in's code (and resources) draws its environment glints when that code does
            // (deliot2023's glintEnvironmentFactor): the renderer then builds the environment's levels for it too.
            method_.environmentGlints = from->environmentGlints;
            // The borrowed resources are built from the shared values of the material the built-in chooses.
            for (const ParamSpec& p : method_.params)
                if (p.name == from->sharedDataMaterial) method_.sharedDataMaterial = from->sharedDataMaterial;
        }
        if (convergeLine) parseConverge(convergeLine, convergeText);
        for (const auto& [line, text] : mapLines) parseMap(line, text);
        return method_;
    }

private:
    void setOnce(int line, const std::string& key, std::string& field, const std::string& value) {
        if (keyLines_.count(key)) fail(line, "'" + key + "' given twice (first on line " + std::to_string(keyLines_[key]) + ")");
        if (value.empty()) fail(line, "'" + key + "' is empty");
        keyLines_[key] = line;
        field = value;
    }

    // NAME = DEFAULT in [MIN, MAX] [int] [log]: MEANING    or    NAME = CHOICE in {A, B, ...}: MEANING
    void parseParam(int line, const std::string& text) {
        static const std::regex shape(R"(^([^=\s]+)\s*=\s*([^\s]+)\s+in\s+(\[[^\]]*\]|\{[^}]*\})\s*([^:]*):\s*(.*)$)");
        std::smatch m;
        if (!std::regex_match(text, m, shape))
            fail(line, "expected 'param: NAME = DEFAULT in [MIN, MAX] [int] [log]: MEANING' or "
                       "'param: NAME = CHOICE in {A, B}: MEANING'");
        ParamSpec spec;
        spec.name = m[1].str();
        std::string defaultText = m[2].str(), range = m[3].str(), flags = trim(m[4].str());
        spec.meaning = trim(m[5].str());
        if (!validName(spec.name)) fail(line, "parameter name '" + spec.name + "' must be lower-case letters, digits and _, starting with a letter");
        std::string upper = spec.name;
        std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
        if (!macros_.insert(upper).second) fail(line, "parameter '" + spec.name + "' declared twice");
        if (spec.meaning.empty()) fail(line, "parameter '" + spec.name + "' has no meaning after the ':'");
        if (int(method_.params.size()) >= kMaxMethodParams)
            fail(line, "more than " + std::to_string(kMaxMethodParams) + " parameters");
        if (range[0] == '{') {
            std::stringstream list(range.substr(1, range.size() - 2));
            for (std::string choice; std::getline(list, choice, ',');) {
                choice = trim(choice);
                if (!validName(choice) && !std::regex_match(choice, std::regex("[A-Za-z0-9_.+-]+")))
                    fail(line, "parameter '" + spec.name + "': choice '" + choice + "' must be one word");
                if (std::find(spec.choices.begin(), spec.choices.end(), choice) != spec.choices.end())
                    fail(line, "parameter '" + spec.name + "': choice '" + choice + "' listed twice");
                spec.choices.push_back(choice);
            }
            if (spec.choices.size() < 2) fail(line, "parameter '" + spec.name + "': an enumeration needs at least two choices");
            if (!flags.empty()) fail(line, "parameter '" + spec.name + "': '" + flags + "' after an enumeration (int and log are for ranges)");
            auto it = std::find(spec.choices.begin(), spec.choices.end(), defaultText);
            if (it == spec.choices.end()) fail(line, "parameter '" + spec.name + "': default '" + defaultText + "' is not one of its choices");
            spec.minValue = 0.0f;
            spec.maxValue = float(spec.choices.size() - 1);
            spec.defaultValue = float(it - spec.choices.begin());
        } else {
            std::string inner = range.substr(1, range.size() - 2);
            size_t comma = inner.find(',');
            if (comma == std::string::npos || !parseNumber(inner.substr(0, comma), spec.minValue) ||
                !parseNumber(inner.substr(comma + 1), spec.maxValue))
                fail(line, "parameter '" + spec.name + "': range must be [MIN, MAX] with two finite numbers");
            if (!(spec.minValue < spec.maxValue)) fail(line, "parameter '" + spec.name + "': range minimum must be below its maximum");
            if (!parseNumber(defaultText, spec.defaultValue)) fail(line, "parameter '" + spec.name + "': default '" + defaultText + "' is not a number");
            if (spec.defaultValue < spec.minValue || spec.defaultValue > spec.maxValue)
                fail(line, "parameter '" + spec.name + "': default " + defaultText + " is outside " + range);
            std::stringstream words(flags);
            for (std::string flag; words >> flag;) {
                if (flag == "int") spec.integer = true;
                else if (flag == "log") spec.logScale = true;
                else fail(line, "parameter '" + spec.name + "': unknown flag '" + flag + "' (int, log)");
            }
            if (spec.integer && spec.defaultValue != std::round(spec.defaultValue))
                fail(line, "parameter '" + spec.name + "': an int parameter needs a whole default");
            if (spec.logScale && spec.maxValue <= 0.0f) fail(line, "parameter '" + spec.name + "': log needs a positive maximum");
        }
        method_.params.push_back(spec);
    }

    // map: NAME = [ln(][SCALE] QUANTITY[^POWER] [alpha^POWER][)] [- PARAM^2/2]: the glint material's quantity feeding a declared
    // parameter (glint_mapping.h; the same text --list-params prints for a built-in's mapping). A parameter
    // without a map line keeps its default on every material (then --set).
    void parseMap(int line, const std::string& text) {
        const std::string shape = "expected 'map: NAME = [ln(][SCALE] QUANTITY[^POWER] [alpha^POWER][)] [- PARAM^2/2]'";
        size_t eq = text.find('=');
        if (eq == std::string::npos) fail(line, shape);
        ParamMapping mapping;
        mapping.param = trim(text.substr(0, eq));
        std::string term = trim(text.substr(eq + 1));
        static const std::regex halfSquare(R"(^(.*\S)\s+-\s*([a-z][a-z0-9_]*)\^2\s*/\s*2$)");
        if (std::smatch m; std::regex_match(term, m, halfSquare)) {
            mapping.minusHalfSquareOf = m[2].str();
            term = m[1].str();
            bool known = false;
            for (const ParamSpec& p : method_.params) known = known || p.name == mapping.minusHalfSquareOf;
            if (!known) fail(line, "map: '" + mapping.minusHalfSquareOf + "' (in '- NAME^2/2') is not a parameter of this header");
        }
        bool declared = false;
        for (const ParamSpec& p : method_.params) declared = declared || p.name == mapping.param;
        if (!declared) fail(line, "map: '" + mapping.param + "' is not a parameter of this header");
        for (const ParamMapping& m : method_.materialMapping)
            if (m.param == mapping.param) fail(line, "map: '" + mapping.param + "' mapped twice");
        if (term.rfind("ln(", 0) == 0) {
            if (term.back() != ')') fail(line, "map: 'ln(' without its closing ')'");
            mapping.log = true;
            term = trim(term.substr(3, term.size() - 4));
        }
        bool haveQuantity = false, haveScale = false;
        std::stringstream words(term);
        for (std::string word; words >> word;) {
            std::string base = word, power;
            if (size_t caret = word.find('^'); caret != std::string::npos) base = word.substr(0, caret), power = word.substr(caret + 1);
            if (base.size() > 2 && base.front() == '(' && base.back() == ')') base = base.substr(1, base.size() - 2);
            float value = 0.0f;
            if (power.empty() && !haveScale && !haveQuantity && parseNumber(base, value)) {
                mapping.scale = value, haveScale = true;
                continue;
            }
            if (!power.empty() && !parseNumber(power, value)) fail(line, "map: power '" + power + "' is not a number");
            if (base == "alpha" && haveQuantity) {
                mapping.alphaPower = power.empty() ? 1.0f : value;
                continue;
            }
            bool known = false;
            for (int q = 0; q <= int(GlintQuantity::Ndf); ++q)
                if (base == glintQuantityName(GlintQuantity(q))) mapping.quantity = GlintQuantity(q), known = true;
            if (!known || haveQuantity)
                fail(line, "map: '" + word + "' is not a quantity (density_per_uv, angular_size, alpha, anisotropy, "
                           "color_variation, color.r, color.g, color.b, ndf) or " + shape.substr(9));
            mapping.power = power.empty() ? 1.0f : value;
            haveQuantity = true;
        }
        if (!haveQuantity) fail(line, "map: no quantity; " + shape);
        mapping.why = "method file, line " + std::to_string(line);
        method_.materialMapping.push_back(mapping);
    }

    // converge: NAME=VALUE[, NAME=VALUE ...], names among the declared parameters.
    void parseConverge(int line, const std::string& text) {
        std::stringstream list(text);
        for (std::string item; std::getline(list, item, ',');) {
            item = trim(item);
            size_t eq = item.find('=');
            if (eq == std::string::npos) fail(line, "converge: expected NAME=VALUE, got '" + item + "'");
            std::string name = trim(item.substr(0, eq)), value = trim(item.substr(eq + 1));
            const ParamSpec* spec = nullptr;
            for (const ParamSpec& p : method_.params)
                if (p.name == name) spec = &p;
            if (!spec) fail(line, "converge: '" + name + "' is not a parameter of this header");
            try {
                method_.convergence[name] = parseParamValue(*spec, value, "converge", name);
            } catch (const Error& e) {
                fail(line, e.what());
            }
        }
        if (method_.convergence.empty()) fail(line, "converge: expected NAME=VALUE");
    }

    std::string label_;
    GlintMethod method_;
    std::map<std::string, int> keyLines_;
    std::set<std::string> macros_;
};

}  // namespace

GlintMethod parseUserMethodHeader(const std::string& text, const std::string& fileLabel) {
    return HeaderParser(fileLabel).parse(text);
}

GlintMethod readUserMethodFile(const fs::path& path) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(path.string() + ": method file not found");
    if (!fs::is_regular_file(path, ec)) throw Error(path.string() + ": method file is not a regular file");
    if (fs::file_size(path, ec) > kMaxMethodFileBytes) throw Error(path.string() + ": method file larger than 4 MiB");
    fs::path canonical = fs::canonical(path, ec);
    if (ec) throw Error(path.string() + ": cannot resolve the path");
    GlintMethod method = parseUserMethodHeader(readTextFile(canonical), displayPath(canonical));
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
            std::string text = readTextFile(it->path());
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
