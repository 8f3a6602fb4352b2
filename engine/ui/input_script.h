// `glimmer view --input-script FILE`: timed input events replayed into the window as if typed, for tests and
// recordings that must not depend on the window system's timing. One event per line, times in seconds from the
// first frame, '#' starts a comment:
//   0.5 down w        key held from 0.5 s (names: a-z, 0-9, f1-f12, shift, space, tab, enter, escape, up,
//   2.5 up w          down, left, right)            ... released at 2.5 s
//   3.0 press f       a press and release (actions: toggles, camera keys)
//   3.2 look 120 -40  mouse look by (dx, dy) pixels, as a captured mouse would
//   4.0 print         one line on stdout: "time T position X Y Z mode walk|fly speed S"
//   4.0 screenshot F  writes the window image (PNG) to F
//   4.5 quit          closes the window
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace glimmer::ui {

struct ScriptEvent {
    enum class Kind { Down, Up, Press, Look, Print, Screenshot, Quit };
    double seconds = 0.0;
    Kind kind = Kind::Print;
    int key = -1;          // GLFW_KEY_* for Down / Up / Press
    float dx = 0, dy = 0;  // Look
    std::string path;      // Screenshot
};

// Parses the file (events sorted by time, ties in file order). Throws glimmer::Error naming FILE:LINE.
std::vector<ScriptEvent> readInputScript(const std::filesystem::path& file);
std::vector<ScriptEvent> parseInputScript(const std::string& text, const std::string& fileName);
// GLFW_KEY_* for a key name ("w", "f5", "shift"), -1 when unknown.
int keyFromName(const std::string& name);

// Hands out the events that are due, one at a time, in order (the window may hold the rest for a later frame).
class ScriptPlayer {
public:
    explicit ScriptPlayer(std::vector<ScriptEvent> events) : events_(std::move(events)) {}
    // The next event due by `seconds`, removed; nullptr when none is due (valid until the next call).
    const ScriptEvent* nextDue(double seconds);
    bool finished() const { return next_ >= events_.size(); }

private:
    std::vector<ScriptEvent> events_;
    size_t next_ = 0;
};

}  // namespace glimmer::ui
