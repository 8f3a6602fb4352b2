// When each key was held, from timestamped press and release events, so that movement is speed x held time
// whatever the frame rate: a key held for part of a frame moves for that part, and a press and release that
// both arrive between two frames still move the camera (a tap counts as held for at least kMinimumTapSeconds,
// since the window system delivers both at the same poll and the true duration is unknown).
#pragma once
#include <map>
#include <vector>

namespace glimmer::ui {

constexpr double kMinimumTapSeconds = 0.1;

class KeyHolds {
public:
    void press(int key, double seconds);
    void release(int key, double seconds);
    void releaseAll(double seconds);
    bool down(int key) const;
    // Seconds of [from, to] during which `key` was held.
    double heldSeconds(int key, double from, double to) const;
    // Drops holds that ended before `seconds` (call once per frame with the frame's start).
    void forgetBefore(double seconds);

private:
    struct Hold {
        double start, end;  // end = +infinity while held
    };
    std::map<int, std::vector<Hold>> holds_;
};

}  // namespace glimmer::ui
