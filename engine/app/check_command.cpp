// glimmer check-method: the interface rules a glint method is held to (checks/method_checks.h), as a table.
// Exit 0 when every rule passes, 1 naming the failed rules.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/cli.h"
#include "core/error.h"
#include "checks/method_checks.h"
#include "glints/user/user_methods.h"
#include "platform/context.h"
#include "reference/discrete_facets/material_check.h"

namespace glimmer {

static const char* kCheckHelp =
    "usage: glimmer check-method PATH.glsl|METHOD [--rules r1,r2] [--size N] [--timing-size N] [--frames N]\n"
    "                            [--rule-seconds S] [--backend egl|osmesa] [--shader-dir DIR]\n"
    "  Runs the interface rules of shaders/glints/README.md on a user method file (or a built-in) and prints a\n"
    "  table: convergence (renders equal smooth at the header's 'converge' values), furnace (area-averaged\n"
    "  int D cos = 1), finite (no NaN/Inf/negative D over a sweep of footprints and angles), cost (lighting pass\n"
    "  relative to smooth, reported) and constant-time (plane25 / plane90 cost like smooth's). Exit 1 names the\n"
    "  rules that failed. --size: convergence renders (default 128); --timing-size, --frames: timing (192, 5).\n"
    "  Each rule runs in a process of its own and fails when it takes longer than --rule-seconds (default 300):\n"
    "  a method that loops until the driver's iteration cap cannot hold the check for hours (renders grow with\n"
    "  the square of --size: raise the limit with it).\n";

namespace {

// The rules that run in one child process: cost and constant-time share their measurements.
std::vector<std::vector<std::string>> ruleGroups(const std::vector<std::string>& wanted) {
    std::vector<std::vector<std::string>> groups;
    auto want = [&](const std::string& rule) {
        return wanted.empty() || std::find(wanted.begin(), wanted.end(), rule) != wanted.end();
    };
    for (const char* rule : {"convergence", "furnace", "finite"})
        if (want(rule)) groups.push_back({rule});
    std::vector<std::string> timing;
    for (const char* rule : {"cost", "constant-time"})
        if (want(rule)) timing.push_back(rule);
    if (!timing.empty()) groups.push_back(timing);
    return groups;
}

std::string joined(const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& item : items) text += (text.empty() ? "" : ",") + item;
    return text;
}

// Runs `args` (this executable's arguments) in a child process, returning what it wrote to stdout; false when it
// ran past `seconds` (then it is killed) or did not exit 0 or 1. Its stderr (progress lines) passes through.
bool runChild(const std::vector<std::string>& args, double seconds, std::string& out, std::string& why) {
    int pipeFds[2];
    if (::pipe2(pipeFds, O_CLOEXEC) != 0) throw Error("check-method: cannot create a pipe");
    pid_t pid = ::fork();
    if (pid < 0) throw Error("check-method: cannot start a process");
    if (pid == 0) {
        ::dup2(pipeFds[1], STDOUT_FILENO);
        std::vector<char*> argv;
        std::vector<std::string> copy = args;
        for (std::string& a : copy) argv.push_back(a.data());
        argv.push_back(nullptr);
        ::execv("/proc/self/exe", argv.data());
        _exit(127);
    }
    ::close(pipeFds[1]);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    bool timedOut = false;
    for (;;) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
        if (left <= 0) {
            timedOut = true;
            break;
        }
        pollfd fd{pipeFds[0], POLLIN, 0};
        int ready = ::poll(&fd, 1, int(std::min<long long>(left, 1000)));
        if (ready < 0 && errno != EINTR) break;
        if (ready <= 0) continue;
        char buffer[4096];
        ssize_t n = ::read(pipeFds[0], buffer, sizeof buffer);
        if (n <= 0) break;   // the child closed its stdout: it is exiting
        out.append(buffer, size_t(n));
    }
    if (timedOut) ::kill(pid, SIGKILL);
    ::close(pipeFds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    if (timedOut) {
        char text[160];
        std::snprintf(text, sizeof text, "did not finish within %g s (--rule-seconds)", seconds);
        why = text;
        return false;
    }
    if (WIFSIGNALED(status)) {
        why = "its process died from signal " + std::to_string(WTERMSIG(status));
        return false;
    }
    if (!WIFEXITED(status) || (WEXITSTATUS(status) != 0 && WEXITSTATUS(status) != 1)) {
        why = "its process exited with status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        return false;
    }
    return true;
}

}  // namespace

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
    const int ruleSeconds = args.intValue("--rule-seconds", 300, 1, 86400);
    const std::string backend = args.valueOr("--backend", "egl");
    options.backend = parseHeadlessBackend(backend);
    if (auto dir = args.value("--shader-dir")) options.shaderRoot = *dir;
    if (auto rules = args.value("--rules")) {
        std::stringstream list(*rules);
        for (std::string rule; std::getline(list, rule, ',');)
            if (!rule.empty()) options.rules.push_back(rule);
        if (options.rules.empty()) throw UsageError("--rules: expected a comma-separated list");
    }
    // The child of a per-rule run (below): runs its rules and prints their results as JSON, no table.
    const bool child = args.flag("--rule-child");
    args.finish();
    for (const std::string& rule : options.rules)
        if (std::find(checks::ruleNames().begin(), checks::ruleNames().end(), rule) == checks::ruleNames().end())
            throw UsageError("--rules: unknown rule '" + rule + "' (rules: convergence, furnace, finite, cost, constant-time, physical-material)");
    // A path (anything with a slash or a .glsl ending) is a method file; otherwise a method of the table.
    bool isFile = target.find('/') != std::string::npos || (target.size() > 5 && target.substr(target.size() - 5) == ".glsl");
    std::string id = resolveGlintMethod(isFile ? "file:" + target : target, "check-method");
    options.progress = [](const std::string& line) { std::fprintf(stderr, "glimmer: check-method: %s\n", line.c_str()); };
    if (child) {
        checks::CheckReport report = checks::checkMethod(id, options);
        nlohmann::json results = nlohmann::json::array();
        for (const checks::RuleResult& r : report.results)
            results.push_back({{"rule", r.rule}, {"status", r.status}, {"measured", r.measured}, {"limit", r.limit}});
        std::printf("%s\n", results.dump().c_str());
        return 0;
    }
    // Each rule (cost with constant-time) in a process of its own, killed past --rule-seconds: GL work cannot be
    // interrupted in process, and a method whose loops run to llvmpipe's cap made one rule take hours.
    checks::CheckReport report;
    report.method = id;
    for (const std::vector<std::string>& group : ruleGroups(options.rules)) {
        std::vector<std::string> childArgs = {"glimmer", "check-method", target, "--rules", joined(group),
                                              "--size", std::to_string(options.size),
                                              "--timing-size", std::to_string(options.timingSize),
                                              "--frames", std::to_string(options.timingFrames), "--backend", backend,
                                              "--rule-child"};
        if (!options.shaderRoot.empty()) childArgs.insert(childArgs.end(), {"--shader-dir", options.shaderRoot.string()});
        std::string out, why;
        bool finished = runChild(childArgs, double(ruleSeconds), out, why);
        nlohmann::json results = finished ? nlohmann::json::parse(out, nullptr, false) : nlohmann::json();
        if (finished && (!results.is_array() || results.size() != group.size())) {
            finished = false;
            why = "its process gave no result";
        }
        for (size_t i = 0; i < group.size(); ++i) {
            checks::RuleResult r{group[i], "FAIL", why, "finishes within " + std::to_string(ruleSeconds) + " s"};
            if (finished) {
                const nlohmann::json& j = results[i];
                r = {j.value("rule", group[i]), j.value("status", "FAIL"), j.value("measured", ""), j.value("limit", "")};
            }
            report.results.push_back(r);
        }
    }
    std::string materialTable;
    // physical-material renders the method and the CPU reference in this process: both are bounded (fixed views,
    // fixed sizes), and its table is printed below the rules.
    if (options.rules.empty() ||
        std::find(options.rules.begin(), options.rules.end(), "physical-material") != options.rules.end()) {
        facets::MaterialCheckOptions material;
        material.size = options.size;
        material.backend = options.backend;
        material.shaderRoot = options.shaderRoot;
        material.progress = options.progress;
        std::vector<facets::MaterialCheckRow> rows = facets::checkPhysicalMaterial(id, material);
        size_t within = 0;
        for (const facets::MaterialCheckRow& row : rows) within += row.target.all();
        checks::RuleResult rule{"physical-material", "info", "", "4x4 blocks vs the discrete-facet reference: CV, p99.9/mean within 1.5x, dark within 0.1, mean within 5 %"};
        rule.measured = std::to_string(within) + " of " + std::to_string(rows.size()) + " views within the target (table below)";
        report.results.push_back(rule);
        materialTable = facets::formatMaterialTable(rows);
    }
    std::fputs(checks::formatTable(report).c_str(), stdout);
    if (!materialTable.empty()) std::printf("\nphysical-material (issue 36, docs/glint_statistics.md):\n%s", materialTable.c_str());
    std::fflush(stdout);
    if (report.passed()) return 0;
    std::string failed;
    for (const std::string& rule : report.failedRules()) failed += (failed.empty() ? "" : ", ") + rule;
    std::fprintf(stderr, "glimmer: check-method %s: rule failed: %s\n", id.c_str(), failed.c_str());
    return 1;
}

}  // namespace glimmer
