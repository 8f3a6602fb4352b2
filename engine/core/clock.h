// Wall-clock timing. On llvmpipe GPU timer queries time the submit, not the work, so every CPU-side timing
// of GL work must close with glFinish() before reading the clock.
#pragma once
#include <chrono>

namespace glimmer {

class Stopwatch {
public:
    Stopwatch() : start_(std::chrono::steady_clock::now()) {}
    void restart() { start_ = std::chrono::steady_clock::now(); }
    double elapsedMs() const {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    std::chrono::steady_clock::time_point start_;
};

}  // namespace glimmer
