// The header block of a user method file (glints/user/user_methods.h, docs/user_methods.md): a GLSL comment opening with
// "/* glimmer-method" whose "key: value" lines declare the method's name, citation, parameters, material mapping
// and convergence values. GL-free, so the method-file fuzz target can link it. Every line is parsed by hand in
// time linear in its length (no backtracking regular expression: a 40 kB meaning must not exhaust the stack).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "core/params.h"
#include "glints/glint_mapping.h"

namespace glimmer {

// The most parameters a method may declare (the per-material parameter block's capacity, glints/methods.h).
constexpr int kMaxUserMethodParams = 64;

struct MethodHeader {
    std::string id, title, citation;
    std::string resourcesFrom;          // "resources:" value ("" = none)
    std::vector<ParamSpec> params;
    std::vector<ParamMapping> materialMapping;
    ParamValues convergence;
};

// Checks a "resources:" value; returns "" when accepted, else the reason (becomes "<label>:<line>: <reason>").
using ResourcesCheck = std::function<std::string(const std::string& builtIn)>;

// Parses the header of `text`. Throws Error "<label>:<line>: message" naming the offending line.
MethodHeader parseMethodHeader(const std::string& text, const std::string& label, const ResourcesCheck& checkResources);

// Lower-case letters, digits and '_', starting with a letter, at most 48 characters: method, parameter names.
bool isMethodName(const std::string& name);

}  // namespace glimmer
