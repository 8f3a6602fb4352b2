// Errors the user can act on. Everything that fails because of input (files, flags, shaders, contexts) throws
// glimmer::Error with one line naming the culprit; the executable prints it and exits non-zero.
#pragma once
#include <stdexcept>
#include <string>

namespace glimmer {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Bad command-line usage: same as Error but reported with exit code 2.
class UsageError : public Error {
public:
    explicit UsageError(const std::string& message) : Error(message) {}
};

}  // namespace glimmer
