// Timing of the passes of a frame, one PassScope per pass (its debug group and its timer):
// - Measure (--stats, bench): glFinish before and after the pass, wall clock between, and a GL_TIME_ELAPSED query
//   read at once (meaningful on real GPUs only; llvmpipe times the submit, not the work).
// - Async (the window): one GL_TIME_ELAPSED query per pass, read kFrames frames later and only once every query of
//   that frame is available: no glFinish, no stall; timings() then holds gpuMs (wallMs 0) of an older frame.
// - Off: debug groups only.
// Only queries begun and ended in the frame being read are read, and a GPU time longer than the wall time that
// contained the pass is no result (gpuMs NaN; --stats writes null): llvmpipe bins glBeginQuery into the scene of the
// framebuffer the driver last drew to, and when that has no tiles (the first pass of the first frame on a
// surfaceless EGL context) no thread executes the begin and the query returns the end timestamp itself, the
// machine's uptime (issue 19: a `gbuffer` time of 1854958 ms).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/clock.h"
#include "gl/handles.h"

namespace glimmer {

struct PassTiming {
    std::string name;
    double wallMs = 0.0;   // wall clock around glFinish (meaningful everywhere, adds sync points)
    double gpuMs = 0.0;    // GL_TIME_ELAPSED (meaningful on real GPUs only; llvmpipe times the submit); NaN: none
};

class PassTimer {
public:
    enum class Mode { Off, Measure, Async };
    static constexpr size_t kFrames = 3;

    // Starts a frame. Async: first reads the frame issued kFrames frames ago when all its results are available
    // (timings() keeps the previous readout otherwise). Measure and Off: timings() starts empty.
    void beginFrame(Mode mode);
    const std::vector<PassTiming>& timings() const { return timings_; }
    // Forgets the readout and the frames still in flight: after a change of the frame's passes (a new method), so
    // the window lists no pass of the previous frames while the new programs compile (seconds of frames on
    // llvmpipe); timings() is empty until a frame issued after it reads back.
    void discard();
    // Measure mode: a pass timed elsewhere (on-demand CPU/compute work with its own wall clock).
    void recordWallOnly(const std::string& name, double wallMs);

private:
    friend class PassScope;
    void begin(const char* name);
    void end();

    struct Slot {
        std::vector<gl::Query> queries;
        std::vector<std::string> names;   // names[i] was timed by queries[i], begun and ended in this slot's frame
        Stopwatch issued;                 // since the slot's frame began: bounds a plausible result
    };
    GLuint queryFor(Slot& slot, size_t index);
    void readBack(Slot& slot);

    Mode mode_ = Mode::Off;
    std::vector<PassTiming> timings_;
    std::array<Slot, kFrames> async_;
    Slot measure_;
    size_t frame_ = 0;
    bool open_ = false;
    std::string openName_;
    Stopwatch clock_;
};

// One pass: debug group and timer for its lifetime. Scopes do not nest.
class PassScope {
public:
    PassScope(PassTimer& timer, const char* name);
    ~PassScope();
    PassScope(const PassScope&) = delete;
    PassScope& operator=(const PassScope&) = delete;

private:
    PassTimer& timer_;
};

}  // namespace glimmer
