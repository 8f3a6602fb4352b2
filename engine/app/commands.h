// The subcommands of the `glimmer` executable. Each returns the process exit code.
#pragma once
#include <string>
#include <vector>

namespace glimmer {

int runRenderCommand(const std::vector<std::string>& args);
int runViewCommand(const std::vector<std::string>& args);
int runBenchCommand(const std::vector<std::string>& args);
int runCheckCommand(const std::vector<std::string>& args);   // check-method

}  // namespace glimmer
