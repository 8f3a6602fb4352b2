// Minimal command-line option reader: `--name value`, `--name=value`, repeated options, boolean flags.
// Unknown or leftover arguments are errors naming the argument.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace glimmer {

class ArgReader {
public:
    ArgReader(std::string command, std::vector<std::string> args);

    bool flag(const std::string& name);                               // --name
    std::optional<std::string> value(const std::string& name);        // last --name VALUE
    std::vector<std::string> values(const std::string& name);         // every --name VALUE
    std::string valueOr(const std::string& name, const std::string& fallback);
    int intValue(const std::string& name, int fallback, int minValue, int maxValue);
    // Throws UsageError naming the first argument nobody asked for.
    void finish() const;

private:
    std::string command_;
    std::vector<std::string> args_;
    std::vector<bool> used_;
};

// Parses WxH (e.g. 1280x720) within [1, 16384]; throws UsageError naming `flag`.
void parseSize(const std::string& text, const char* flag, int& width, int& height);

}  // namespace glimmer
