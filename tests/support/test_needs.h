// What a test suite needs beyond the CPU, declared next to its tests; the ctest label follows from it
// (tests/CMakeLists.txt, tests/support/test_main.cpp):
//
//   (nothing declared)                  fast    no GL context, no child process
//   GLIMMER_SUITE_NEEDS(S, GlContext)   gl      creates a GL context
//   GLIMMER_SUITE_NEEDS(S, Process)     gl      starts a process (the glimmer executable, python, a shell)
//   GLIMMER_SUITE_NEEDS(S, Window)      window  a window under Xvfb
//
// and any test whose full name contains "Golden" is labelled golden instead of fast or gl. A new suite is fast until it
// says otherwise, and the test support checks that at run time: a test labelled fast that creates a GL context or
// starts a process fails, naming the declaration it lacks.
#pragma once
#include <map>
#include <string>

namespace glimmer::test {

enum class Need { GlContext, Process, Window };

inline std::map<std::string, Need>& declaredSuiteNeeds() {
    static std::map<std::string, Need> needs;
    return needs;
}

inline bool declareSuiteNeed(const char* suite, Need need) {
    declaredSuiteNeeds()[suite] = need;
    return true;
}

}  // namespace glimmer::test

#define GLIMMER_SUITE_NEEDS(suite, need)                                      \
    [[maybe_unused]] static const bool glimmer_suite_needs_##suite##_##need = \
        ::glimmer::test::declareSuiteNeed(#suite, ::glimmer::test::Need::need)
