// glimmer check-method: the interface rules a glint method is held to (checks/method_checks.h), as a table.
// Exit 0 when every rule passes, 1 naming the failed rules.
#include <cstdio>
#include <sstream>

#include "app/commands.h"
#include "core/cli.h"
#include "core/error.h"
#include "checks/method_checks.h"
#include "glints/user/user_methods.h"
#include "platform/context.h"

namespace glimmer {

static const char* kCheckHelp =
    "usage: glimmer check-method PATH.glsl|METHOD [--rules r1,r2] [--size N] [--timing-size N] [--frames N]\n"
    "                            [--backend egl|osmesa] [--shader-dir DIR]\n"
    "  Runs the interface rules of shaders/glints/README.md on a user method file (or a built-in) and prints a\n"
    "  table: convergence (renders equal smooth at the header's 'converge' values), furnace (area-averaged\n"
    "  int D cos = 1), finite (no NaN/Inf/negative D over a sweep of footprints and angles), cost (lighting pass\n"
    "  relative to smooth, reported) and constant-time (plane25 / plane90 cost like smooth's). Exit 1 names the\n"
    "  rules that failed. --size: convergence renders (default 128); --timing-size, --frames: timing (192, 5).\n";

int runCheckCommand(const std::vector<std::string>& argList) {
    if (argList.empty()) throw UsageError("check-method: expected a method file or name (glimmer check-method --help)");
    if (argList[0] == "--help") { std::fputs(kCheckHelp, stdout); return 0; }
    std::string target = argList[0];
    if (target.rfind("--", 0) == 0) throw UsageError("check-method: the first argument must be a method file or name");
    ArgReader args("check-method", std::vector<std::string>(argList.begin() + 1, argList.end()));
    checks::CheckOptions options;
    options.size = args.intValue("--size", 128, 16, 1024);
    options.timingSize = args.intValue("--timing-size", 192, 16, 2048);
    options.timingFrames = args.intValue("--frames", 5, 1, 1000);
    options.backend = parseHeadlessBackend(args.valueOr("--backend", "egl"));
    if (auto dir = args.value("--shader-dir")) options.shaderRoot = *dir;
    if (auto rules = args.value("--rules")) {
        std::stringstream list(*rules);
        for (std::string rule; std::getline(list, rule, ',');)
            if (!rule.empty()) options.rules.push_back(rule);
        if (options.rules.empty()) throw UsageError("--rules: expected a comma-separated list");
    }
    args.finish();
    // A path (anything with a slash or a .glsl ending) is a method file; otherwise a method of the table.
    bool isFile = target.find('/') != std::string::npos || (target.size() > 5 && target.substr(target.size() - 5) == ".glsl");
    std::string id = resolveGlintMethod(isFile ? "file:" + target : target, "check-method");
    options.progress = [](const std::string& line) { std::fprintf(stderr, "glimmer: check-method: %s\n", line.c_str()); };
    checks::CheckReport report = checks::checkMethod(id, options);
    std::fputs(checks::formatTable(report).c_str(), stdout);
    std::fflush(stdout);
    if (report.passed()) return 0;
    std::string failed;
    for (const std::string& rule : report.failedRules()) failed += (failed.empty() ? "" : ", ") + rule;
    std::fprintf(stderr, "glimmer: check-method %s: rule failed: %s\n", id.c_str(), failed.c_str());
    return 1;
}

}  // namespace glimmer
