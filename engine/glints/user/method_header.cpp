#include "glints/user/method_header.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>

#include "core/error.h"

namespace glimmer {
namespace {

constexpr const char* kHeaderOpen = "/* glimmer-method";

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }
bool isLower(char c) { return c >= 'a' && c <= 'z'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

std::string trim(const std::string& s) {
    size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string::npos) return "";
    size_t b = s.find_last_not_of(" \t\r");
    return s.substr(a, b - a + 1);
}

// A choice of an enumeration: one word of letters, digits and _ . + -.
bool isChoiceWord(const std::string& word) {
    if (word.empty()) return false;
    for (char c : word)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '+' || c == '-')) return false;
    return true;
}

// Strictly parsed finite number (no trailing text).
bool parseNumber(const std::string& text, float& value) {
    std::string t = trim(text);
    if (t.empty()) return false;
    char* end = nullptr;
    value = std::strtof(t.c_str(), &end);
    return end == t.c_str() + t.size() && std::isfinite(value);
}

// The parts of "NAME = DEFAULT in [MIN, MAX] FLAGS: MEANING" or "NAME = CHOICE in {A, B}: MEANING".
struct ParamLine {
    std::string name, defaultText, range, flags, meaning;
};

// Reads the shape above from left to right, each part ending at the first character that cannot belong to it.
bool splitParamLine(const std::string& text, ParamLine& out) {
    size_t at = 0, n = text.size();
    auto skipSpaces = [&] { while (at < n && isSpace(text[at])) ++at; };
    size_t start = at;
    while (at < n && text[at] != '=' && !isSpace(text[at])) ++at;   // NAME: no '=' and no blank
    if (at == start) return false;
    out.name = text.substr(start, at - start);
    skipSpaces();
    if (at >= n || text[at] != '=') return false;
    ++at;
    skipSpaces();
    start = at;
    while (at < n && !isSpace(text[at])) ++at;                      // DEFAULT: no blank
    if (at == start) return false;
    out.defaultText = text.substr(start, at - start);
    size_t blanks = at;
    skipSpaces();
    if (at == blanks || text.compare(at, 2, "in") != 0) return false;
    at += 2;
    blanks = at;
    skipSpaces();
    if (at == blanks || at >= n) return false;
    char close = text[at] == '[' ? ']' : text[at] == '{' ? '}' : '\0';
    if (!close) return false;
    size_t end = text.find(close, at + 1);
    if (end == std::string::npos) return false;
    out.range = text.substr(at, end + 1 - at);
    at = end + 1;
    skipSpaces();
    size_t colon = text.find(':', at);
    if (colon == std::string::npos) return false;
    out.flags = text.substr(at, colon - at);
    at = colon + 1;
    skipSpaces();
    out.meaning = text.substr(at);
    return true;
}

// "TERM - NAME^2/2" at the end of a map term: splits off NAME (a parameter name) and returns the TERM before it.
bool splitHalfSquare(const std::string& term, std::string& before, std::string& name) {
    size_t i = term.size();
    auto back = [&](char c) {
        if (i == 0 || term[i - 1] != c) return false;
        --i;
        return true;
    };
    auto skipSpacesBack = [&] { while (i > 0 && isSpace(term[i - 1])) --i; };
    if (!back('2')) return false;
    skipSpacesBack();
    if (!back('/')) return false;
    skipSpacesBack();
    if (!back('2') || !back('^')) return false;
    size_t nameEnd = i;
    while (i > 0 && (isLower(term[i - 1]) || isDigit(term[i - 1]) || term[i - 1] == '_')) --i;
    if (i == nameEnd || !isLower(term[i])) return false;
    name = term.substr(i, nameEnd - i);
    skipSpacesBack();
    if (!back('-')) return false;
    size_t minus = i;
    skipSpacesBack();
    if (i == minus || i == 0) return false;   // at least one blank before '-', and a term before that
    before = term.substr(0, i);
    return true;
}

class HeaderParser {
public:
    HeaderParser(const std::string& label, const ResourcesCheck& checkResources)
        : label_(label), checkResources_(checkResources) {}

    [[noreturn]] void fail(int line, const std::string& message) const {
        throw Error(label_ + ":" + std::to_string(line) + ": " + message);
    }

    MethodHeader parse(const std::string& text) {
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
                if (key == "name") setOnce(number, "name", header_.id, value);
                else if (key == "title") setOnce(number, "title", header_.title, value);
                else if (key == "citation") setOnce(number, "citation", header_.citation, value);
                else if (key == "resources") setOnce(number, "resources", header_.resourcesFrom, value);
                else if (key == "param") parseParam(number, value);
                else if (key == "map") mapLines.push_back({number, value});
                else if (key == "converge") {
                    if (convergeLine) fail(number, "'converge' given twice (first on line " + std::to_string(convergeLine) + ")");
                    convergeLine = number;
                    convergeText = value;
                } else {
                    fail(number, "unknown key '" + key.substr(0, 64) + "' (keys: name, title, citation, param, map, converge, resources)");
                }
            }
            if (closed) break;
        }
        if (!inside) fail(1, "no header block: the file must contain a comment opening with '" + std::string(kHeaderOpen) + "'");
        if (!closed) fail(openLine, "the header block opened here is not closed with */");
        if (header_.id.empty()) fail(openLine, "the header has no 'name'");
        if (!isMethodName(header_.id)) fail(keyLines_["name"], "name '" + header_.id.substr(0, 64) + "' must be lower-case letters, digits and _, starting with a letter (at most 48)");
        if (header_.citation.empty()) fail(openLine, "the header has no 'citation' (say where the idea comes from)");
        if (header_.title.empty()) header_.title = header_.id;
        if (!header_.resourcesFrom.empty())
            if (std::string problem = checkResources_ ? checkResources_(header_.resourcesFrom) : ""; !problem.empty())
                fail(keyLines_["resources"], problem);
        if (convergeLine) parseConverge(convergeLine, convergeText);
        for (const auto& [line, text] : mapLines) parseMap(line, text);
        return header_;
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
        ParamLine parts;
        if (!splitParamLine(text, parts))
            fail(line, "expected 'param: NAME = DEFAULT in [MIN, MAX] [int] [log]: MEANING' or "
                       "'param: NAME = CHOICE in {A, B}: MEANING'");
        ParamSpec spec;
        spec.name = parts.name;
        const std::string& defaultText = parts.defaultText;
        const std::string& range = parts.range;
        std::string flags = trim(parts.flags);
        spec.meaning = trim(parts.meaning);
        if (!isMethodName(spec.name)) fail(line, "parameter name '" + spec.name.substr(0, 64) + "' must be lower-case letters, digits and _, starting with a letter");
        std::string upper = spec.name;
        std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
        if (!macros_.insert(upper).second) fail(line, "parameter '" + spec.name + "' declared twice");
        if (spec.meaning.empty()) fail(line, "parameter '" + spec.name + "' has no meaning after the ':'");
        if (int(header_.params.size()) >= kMaxUserMethodParams)
            fail(line, "more than " + std::to_string(kMaxUserMethodParams) + " parameters");
        if (range[0] == '{') {
            std::stringstream list(range.substr(1, range.size() - 2));
            for (std::string choice; std::getline(list, choice, ',');) {
                choice = trim(choice);
                if (!isChoiceWord(choice))
                    fail(line, "parameter '" + spec.name + "': choice '" + choice.substr(0, 64) + "' must be one word");
                if (std::find(spec.choices.begin(), spec.choices.end(), choice) != spec.choices.end())
                    fail(line, "parameter '" + spec.name + "': choice '" + choice + "' listed twice");
                spec.choices.push_back(choice);
            }
            if (spec.choices.size() < 2) fail(line, "parameter '" + spec.name + "': an enumeration needs at least two choices");
            if (!flags.empty()) fail(line, "parameter '" + spec.name + "': '" + flags.substr(0, 64) + "' after an enumeration (int and log are for ranges)");
            auto it = std::find(spec.choices.begin(), spec.choices.end(), defaultText);
            if (it == spec.choices.end()) fail(line, "parameter '" + spec.name + "': default '" + defaultText.substr(0, 64) + "' is not one of its choices");
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
            if (!parseNumber(defaultText, spec.defaultValue)) fail(line, "parameter '" + spec.name + "': default '" + defaultText.substr(0, 64) + "' is not a number");
            if (spec.defaultValue < spec.minValue || spec.defaultValue > spec.maxValue)
                fail(line, "parameter '" + spec.name + "': default " + defaultText + " is outside " + range);
            std::stringstream words(flags);
            for (std::string flag; words >> flag;) {
                if (flag == "int") spec.integer = true;
                else if (flag == "log") spec.logScale = true;
                else fail(line, "parameter '" + spec.name + "': unknown flag '" + flag.substr(0, 64) + "' (int, log)");
            }
            if (spec.integer && spec.defaultValue != std::round(spec.defaultValue))
                fail(line, "parameter '" + spec.name + "': an int parameter needs a whole default");
            if (spec.logScale && spec.maxValue <= 0.0f) fail(line, "parameter '" + spec.name + "': log needs a positive maximum");
        }
        header_.params.push_back(spec);
    }

    // map: NAME = [ln(][SCALE] QUANTITY[^POWER] [alpha^POWER][)] [- PARAM^2/2], or NAME = NUMBER (a constant): the
    // glint material's quantity feeding a declared parameter (glint_mapping.h; the same text --list-params prints
    // for a built-in's mapping). A parameter without a map line keeps its default on every material (then --set).
    void parseMap(int line, const std::string& text) {
        const std::string shape = "expected 'map: NAME = [ln(][SCALE] QUANTITY[^POWER] [alpha^POWER][)] [- PARAM^2/2]'";
        size_t eq = text.find('=');
        if (eq == std::string::npos) fail(line, shape);
        ParamMapping mapping;
        mapping.param = trim(text.substr(0, eq));
        std::string term = trim(text.substr(eq + 1));
        if (std::string before, name; splitHalfSquare(term, before, name)) {
            mapping.minusHalfSquareOf = name;
            term = before;
            bool known = false;
            for (const ParamSpec& p : header_.params) known = known || p.name == mapping.minusHalfSquareOf;
            if (!known) fail(line, "map: '" + mapping.minusHalfSquareOf.substr(0, 64) + "' (in '- NAME^2/2') is not a parameter of this header");
        }
        bool declared = false;
        for (const ParamSpec& p : header_.params) declared = declared || p.name == mapping.param;
        if (!declared) fail(line, "map: '" + mapping.param.substr(0, 64) + "' is not a parameter of this header");
        for (const ParamMapping& m : header_.materialMapping)
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
            if (!power.empty() && !parseNumber(power, value)) fail(line, "map: power '" + power.substr(0, 64) + "' is not a number");
            if (base == "alpha" && haveQuantity) {
                mapping.alphaPower = power.empty() ? 1.0f : value;
                continue;
            }
            bool known = false;
            for (int q = 0; q <= int(GlintQuantity::Ndf); ++q)
                if (base == glintQuantityName(GlintQuantity(q))) mapping.quantity = GlintQuantity(q), known = true;
            if (!known || haveQuantity)
                fail(line, "map: '" + word.substr(0, 64) + "' is not a quantity (density_per_uv, angular_size, alpha, anisotropy, "
                           "color_variation, color.r, color.g, color.b, ndf) or " + shape.substr(9));
            mapping.power = power.empty() ? 1.0f : value;
            haveQuantity = true;
        }
        // A number alone is a constant (e.g. 'map: density_randomization = 0', switching a knob off on every
        // material, as --list-params prints such rows): quantity^0.
        if (!haveQuantity && haveScale && !mapping.log && mapping.minusHalfSquareOf.empty()) {
            mapping.power = 0.0f;
            haveQuantity = true;
        }
        if (!haveQuantity) fail(line, "map: no quantity; " + shape);
        mapping.why = "method file, line " + std::to_string(line);
        header_.materialMapping.push_back(mapping);
    }

    // converge: NAME=VALUE[, NAME=VALUE ...], names among the declared parameters.
    void parseConverge(int line, const std::string& text) {
        std::stringstream list(text);
        for (std::string item; std::getline(list, item, ',');) {
            item = trim(item);
            size_t eq = item.find('=');
            if (eq == std::string::npos) fail(line, "converge: expected NAME=VALUE, got '" + item.substr(0, 64) + "'");
            std::string name = trim(item.substr(0, eq)), value = trim(item.substr(eq + 1));
            const ParamSpec* spec = nullptr;
            for (const ParamSpec& p : header_.params)
                if (p.name == name) spec = &p;
            if (!spec) fail(line, "converge: '" + name.substr(0, 64) + "' is not a parameter of this header");
            try {
                header_.convergence[name] = parseParamValue(*spec, value, "converge", name);
            } catch (const Error& e) {
                fail(line, e.what());
            }
        }
        if (header_.convergence.empty()) fail(line, "converge: expected NAME=VALUE");
    }

    std::string label_;
    const ResourcesCheck& checkResources_;
    MethodHeader header_;
    std::map<std::string, int> keyLines_;
    std::set<std::string> macros_;
};

}  // namespace

bool isMethodName(const std::string& name) {
    if (name.empty() || name.size() > 48 || !isLower(name[0])) return false;
    for (char c : name)
        if (!(isLower(c) || isDigit(c) || c == '_')) return false;
    return true;
}

MethodHeader parseMethodHeader(const std::string& text, const std::string& label, const ResourcesCheck& checkResources) {
    return HeaderParser(label, checkResources).parse(text);
}

}  // namespace glimmer
