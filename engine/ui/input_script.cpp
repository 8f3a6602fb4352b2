#include "ui/input_script.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/files.h"

namespace glimmer::ui {

int keyFromName(const std::string& raw) {
    std::string name = raw;
    for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (name.size() == 1 && name[0] >= 'a' && name[0] <= 'z') return GLFW_KEY_A + (name[0] - 'a');
    if (name.size() == 1 && name[0] >= '0' && name[0] <= '9') return GLFW_KEY_0 + (name[0] - '0');
    if (name.size() >= 2 && name[0] == 'f' && std::all_of(name.begin() + 1, name.end(), ::isdigit)) {
        int n = std::stoi(name.substr(1));
        if (n >= 1 && n <= 12) return GLFW_KEY_F1 + (n - 1);
    }
    static const std::pair<const char*, int> named[] = {
        {"shift", GLFW_KEY_LEFT_SHIFT}, {"space", GLFW_KEY_SPACE}, {"tab", GLFW_KEY_TAB},
        {"enter", GLFW_KEY_ENTER},      {"escape", GLFW_KEY_ESCAPE}, {"up", GLFW_KEY_UP},
        {"down", GLFW_KEY_DOWN},        {"left", GLFW_KEY_LEFT},   {"right", GLFW_KEY_RIGHT}};
    for (const auto& [n, key] : named)
        if (name == n) return key;
    return -1;
}

std::vector<ScriptEvent> parseInputScript(const std::string& text, const std::string& fileName) {
    std::vector<ScriptEvent> events;
    std::istringstream lines(text);
    std::string line;
    for (int number = 1; std::getline(lines, line); ++number) {
        if (size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        std::istringstream words(line);
        std::string timeText, kind;
        if (!(words >> timeText)) continue;
        auto fail = [&](const std::string& why) {
            return Error(fileName + ":" + std::to_string(number) + ": " + why);
        };
        ScriptEvent event;
        char* end = nullptr;
        event.seconds = std::strtod(timeText.c_str(), &end);
        if (*end != '\0' || !(event.seconds >= 0.0) || !std::isfinite(event.seconds))
            throw fail("'" + timeText + "' is not a time in seconds");
        if (!(words >> kind)) throw fail("expected an event after the time");
        if (kind == "down" || kind == "up" || kind == "press") {
            std::string keyName;
            if (!(words >> keyName)) throw fail(kind + ": expected a key name");
            event.key = keyFromName(keyName);
            if (event.key < 0) throw fail("unknown key '" + keyName + "'");
            event.kind = kind == "down" ? ScriptEvent::Kind::Down
                                        : (kind == "up" ? ScriptEvent::Kind::Up : ScriptEvent::Kind::Press);
        } else if (kind == "look") {
            if (!(words >> event.dx >> event.dy)) throw fail("look: expected dx dy in pixels");
            event.kind = ScriptEvent::Kind::Look;
        } else if (kind == "print") {
            event.kind = ScriptEvent::Kind::Print;
        } else if (kind == "screenshot") {
            if (!(words >> event.path)) throw fail("screenshot: expected a file name");
            event.kind = ScriptEvent::Kind::Screenshot;
        } else if (kind == "quit") {
            event.kind = ScriptEvent::Kind::Quit;
        } else {
            throw fail("unknown event '" + kind + "' (down, up, press, look, print, screenshot, quit)");
        }
        std::string extra;
        if (words >> extra) throw fail("unexpected '" + extra + "'");
        events.push_back(event);
    }
    std::stable_sort(events.begin(), events.end(),
                     [](const ScriptEvent& a, const ScriptEvent& b) { return a.seconds < b.seconds; });
    return events;
}

std::vector<ScriptEvent> readInputScript(const std::filesystem::path& file) {
    return parseInputScript(readInputFile(file, kInputScriptInput), file.string());
}

const ScriptEvent* ScriptPlayer::nextDue(double seconds) {
    if (next_ < events_.size() && events_[next_].seconds <= seconds) return &events_[next_++];
    return nullptr;
}

}  // namespace glimmer::ui
