#include "render/frame/pass_timer.h"

#include <cmath>
#include <limits>

namespace glimmer {

namespace {

// A GL_TIME_ELAPSED result in ms, or NaN when it cannot be the time of work done within `wallMs` (see the header).
double plausibleGpuMs(GLuint query, double wallMs) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    const double ms = double(ns) * 1e-6;
    constexpr double kSlackMs = 1.0;   // clock granularity and the driver's own bookkeeping
    return ms <= wallMs + kSlackMs ? ms : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

GLuint PassTimer::queryFor(Slot& slot, size_t index) {
    while (slot.queries.size() <= index) {
        GLuint id = 0;
        glCreateQueries(GL_TIME_ELAPSED, 1, &id);
        slot.queries.emplace_back(id);
    }
    return slot.queries[index].id();
}

void PassTimer::readBack(Slot& slot) {
    for (size_t i = 0; i < slot.names.size(); ++i) {
        GLint available = 0;
        glGetQueryObjectiv(slot.queries[i].id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) return;   // never wait: keep the previous readout
    }
    const double wallMs = slot.issued.elapsedMs();   // the whole frame and everything since fit in this
    timings_.clear();
    for (size_t i = 0; i < slot.names.size(); ++i)
        timings_.push_back({slot.names[i], 0.0, plausibleGpuMs(slot.queries[i].id(), wallMs)});
}

void PassTimer::beginFrame(Mode mode) {
    mode_ = mode;
    if (mode == Mode::Async) {
        Slot& slot = async_[frame_ % kFrames];
        if (!slot.names.empty()) readBack(slot);
        slot.names.clear();   // the slot now times this frame (a pending result is discarded by the next begin)
        slot.issued.restart();
        ++frame_;
    } else {
        timings_.clear();
        measure_.names.clear();
    }
}

void PassTimer::discard() {
    timings_.clear();
    for (Slot& slot : async_) slot.names.clear();   // their queries are reused by later frames
}

void PassTimer::recordWallOnly(const std::string& name, double wallMs) {
    if (mode_ == Mode::Measure) timings_.push_back({name, wallMs, 0.0});
}

void PassTimer::begin(const char* name) {
    open_ = mode_ != Mode::Off;
    if (!open_) return;
    openName_ = name;
    if (mode_ == Mode::Measure) {
        glFinish();
        clock_.restart();
        glBeginQuery(GL_TIME_ELAPSED, queryFor(measure_, measure_.names.size()));
    } else {
        Slot& slot = async_[(frame_ + kFrames - 1) % kFrames];
        glBeginQuery(GL_TIME_ELAPSED, queryFor(slot, slot.names.size()));
    }
}

void PassTimer::end() {
    if (!open_) return;
    open_ = false;
    glEndQuery(GL_TIME_ELAPSED);
    if (mode_ == Mode::Measure) {
        glFinish();
        const double wallMs = clock_.elapsedMs();
        const GLuint query = measure_.queries[measure_.names.size()].id();
        measure_.names.push_back(openName_);
        timings_.push_back({openName_, wallMs, plausibleGpuMs(query, wallMs)});
    } else {
        async_[(frame_ + kFrames - 1) % kFrames].names.push_back(openName_);
    }
}

PassScope::PassScope(PassTimer& timer, const char* name) : timer_(timer) {
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name);
    timer_.begin(name);
}

PassScope::~PassScope() {
    timer_.end();
    glPopDebugGroup();
}

}  // namespace glimmer
