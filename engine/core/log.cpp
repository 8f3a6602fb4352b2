#include "core/log.h"

#include <cstdio>
#include <mutex>

namespace glimmer::log {
namespace {
Level g_level = Level::Info;
std::mutex g_mutex;
}  // namespace

void setLevel(Level level) { g_level = level; }
Level level() { return g_level; }

void write(Level level, const std::string& message) {
    static const char* prefix[] = {"debug: ", "", "warning: ", "error: ", ""};
    std::lock_guard lock(g_mutex);
    std::fprintf(stderr, "glimmer: %s%s\n", prefix[static_cast<int>(level)], message.c_str());
}

}  // namespace glimmer::log
