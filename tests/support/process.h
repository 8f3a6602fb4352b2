// Running the glimmer executable from tests and capturing what a user would see.
#pragma once
#include <string>
#include <vector>

namespace glimmer::test {

struct ProcessResult {
    int exitCode = -1;        // exit status, or -1 when the process died from a signal
    int signal = 0;           // the signal that killed it (a crash), 0 otherwise
    std::string out, err;
};

// Runs GLIMMER_EXECUTABLE with `args` (no shell), capturing stdout and stderr.
ProcessResult runGlimmer(const std::vector<std::string>& args, const std::vector<std::string>& extraEnv = {});

// Runs a shell command (with its own redirections) under `xvfb-run -a` with a 1280x720 screen and returns the
// command's exit status. xvfb-run's own status can be its cleanup's (5: its temporary directory could not be
// removed, seen once in CI under ctest -j2), so the command's status is recorded in a file and returned instead.
int runUnderXvfb(const std::string& command, const std::string& screen = "1280x720x24");

// The shared assets folder, or "" when absent (tests that need it skip).
std::string sharedAssetsDir();

// A fresh empty temporary directory under the test output folder.
std::string makeTempDir(const std::string& name);

}  // namespace glimmer::test
