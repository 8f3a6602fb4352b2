#include "support/process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/golden.h"

extern char** environ;

namespace glimmer::test {

static std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

int runUnderXvfb(const std::string& command, const std::string& screen) {
    static int counter = 0;
    std::string codePath =
        (testOutputDir() / ("xvfb-" + std::to_string(getpid()) + "-" + std::to_string(counter++) + ".status")).string();
    std::filesystem::remove(codePath);
    // The command goes to sh as one single-quoted argument: it must not contain single quotes itself.
    std::string wrapped = "xvfb-run -a -s \"-screen 0 " + screen + "\" sh -c '" + command + "; echo $? > " + codePath +
                          "' > /dev/null 2>&1";
    int status = std::system(wrapped.c_str());
    std::ifstream in(codePath);
    int code = -1;
    if (in >> code) return code;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

ProcessResult runGlimmer(const std::vector<std::string>& args, const std::vector<std::string>& extraEnv) {
    static int counter = 0;
    std::string base = (testOutputDir() / ("proc-" + std::to_string(getpid()) + "-" + std::to_string(counter++))).string();
    std::string outPath = base + ".out", errPath = base + ".err";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<std::string> argStrings = {GLIMMER_EXECUTABLE};
    argStrings.insert(argStrings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argStrings) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::vector<std::string> envStrings;
    // extraEnv replaces variables of the same name (getenv would find the inherited one first).
    auto overridden = [&](const std::string& entry) {
        for (const std::string& extra : extraEnv)
            if (extra.substr(0, extra.find('=') + 1) == entry.substr(0, entry.find('=') + 1)) return true;
        return false;
    };
    for (char** e = environ; *e; ++e)
        if (!overridden(*e)) envStrings.push_back(*e);
    envStrings.insert(envStrings.end(), extraEnv.begin(), extraEnv.end());
    std::vector<char*> envp;
    for (std::string& e : envStrings) envp.push_back(e.data());
    envp.push_back(nullptr);
    pid_t pid = 0;
    ProcessResult result;
    if (posix_spawn(&pid, GLIMMER_EXECUTABLE, &actions, nullptr, argv.data(), envp.data()) != 0) {
        result.err = "spawn failed";
        return result;
    }
    posix_spawn_file_actions_destroy(&actions);
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    result.out = slurp(outPath);
    result.err = slurp(errPath);
    std::filesystem::remove(outPath);
    std::filesystem::remove(errPath);
    return result;
}

std::string sharedAssetsDir() {
    std::vector<std::filesystem::path> candidates;
    if (const char* env = std::getenv("GLIMMER_ASSETS_DIR")) candidates.emplace_back(env);
    candidates.push_back(std::filesystem::path(GLIMMER_SOURCE_DIR) / ".." / "shared" / "assets");
    for (const auto& c : candidates)
        if (std::filesystem::is_directory(c)) return std::filesystem::canonical(c).string();
    return "";
}

std::string makeTempDir(const std::string& name) {
    std::filesystem::path dir = testOutputDir() / ("tmp-" + name + "-" + std::to_string(getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

}  // namespace glimmer::test
