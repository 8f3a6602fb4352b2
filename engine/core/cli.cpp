#include "core/cli.h"

#include <cstdlib>

#include "core/error.h"

namespace glimmer {

ArgReader::ArgReader(std::string command, std::vector<std::string> args)
    : command_(std::move(command)), args_(std::move(args)), used_(args_.size(), false) {}

bool ArgReader::flag(const std::string& name) {
    bool found = false;
    for (size_t i = 0; i < args_.size(); ++i)
        if (!used_[i] && args_[i] == name) { used_[i] = true; found = true; }
    return found;
}

std::vector<std::string> ArgReader::values(const std::string& name) {
    std::vector<std::string> out;
    for (size_t i = 0; i < args_.size(); ++i) {
        if (used_[i]) continue;
        if (args_[i] == name) {
            if (i + 1 >= args_.size()) throw UsageError(name + ": missing value");
            used_[i] = used_[i + 1] = true;
            out.push_back(args_[i + 1]);
            ++i;
        } else if (args_[i].rfind(name + "=", 0) == 0) {
            used_[i] = true;
            out.push_back(args_[i].substr(name.size() + 1));
        }
    }
    return out;
}

std::optional<std::string> ArgReader::value(const std::string& name) {
    std::vector<std::string> all = values(name);
    if (all.empty()) return std::nullopt;
    return all.back();
}

std::string ArgReader::valueOr(const std::string& name, const std::string& fallback) {
    return value(name).value_or(fallback);
}

int ArgReader::intValue(const std::string& name, int fallback, int minValue, int maxValue) {
    auto text = value(name);
    if (!text) return fallback;
    char* end = nullptr;
    long v = std::strtol(text->c_str(), &end, 10);
    if (text->empty() || *end != '\0' || v < minValue || v > maxValue)
        throw UsageError(name + ": '" + *text + "' is not an integer in [" + std::to_string(minValue) + ", " +
                         std::to_string(maxValue) + "]");
    return int(v);
}

void ArgReader::finish() const {
    for (size_t i = 0; i < args_.size(); ++i)
        if (!used_[i])
            throw UsageError(command_ + ": unknown argument '" + args_[i] + "' (see glimmer " + command_ + " --help)");
}

void parseSize(const std::string& text, const char* flag, int& width, int& height) {
    size_t x = text.find('x');
    auto bad = [&] { return UsageError(std::string(flag) + ": '" + text + "' is not WxH with 1 <= W, H <= 16384"); };
    if (x == std::string::npos || x == 0 || x + 1 >= text.size()) throw bad();
    char* end = nullptr;
    long w = std::strtol(text.c_str(), &end, 10);
    if (end != text.c_str() + x) throw bad();
    long h = std::strtol(text.c_str() + x + 1, &end, 10);
    if (*end != '\0' || w < 1 || h < 1 || w > 16384 || h > 16384) throw bad();
    width = int(w);
    height = int(h);
}

}  // namespace glimmer
